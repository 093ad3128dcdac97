// Direct SPH of Stokes flow through the periodic lattice of cylinders at a coarse resolution (n = 48), through the
// direct_sph_validation kind's permeability path (experiments/kinds/permeability_validation.cpp): steady state by
// the permeability itself, k against the collocation reference, for both radii of issue 21 (a = 0.2 L, 0.3 L).
//
// What the resolution study measured (results/cylinders/direct/, n = 48, 96, 192): the zero-velocity solid puts
// the no-slip surface about 0.4 lattice spacings inside the nominal cylinder at every n (the channels' known
// ~eps'/2 offset, DESIGN.md par. 6), so k is high by a first-order error. The tests hold the n = 48 figures to
// bands around that: the effective radius shift within [0.25, 0.6] spacings (at a = 0.2 L a shift of 0.15 spacing
// moves k by ~3 %, so the band admits 0.40 +- 0.15 / -0.2 and fails on a lost or doubled offset, e.g. a solid whose
// particles are not held, or a missing fluid-solid pair), the particles within half a spacing of their sites and
// the density within 1e-3 (Stokes: rho g L / (rho c^2) = 1e-4). Both runs take ~10 s on one core.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/permeability_validation.hpp"

using namespace closurelab;

namespace {

json run_lattice(double a) {
  const auto scene = builtin_registry().scenes.create(
      json{{"name", "cylinder-lattice"}, {"n", 48}, {"radius_over_length", a}}, "/scene");
  SphRunOptions opt;
  opt.steady_tolerance = 1e-4;  // as experiments/cylinders/direct.json: the drift after the plateau is ~1e-4 per window
  opt.steady_window = 150;  // 1/60 model time at n = 48 (dt = 0.25 eps'^2 rho / mu)
  opt.max_time = 1.0;
  const json row = run_permeability_validation(*scene, opt);
  std::cout << "a/L = " << a << ": " << row.at("errors").at("permeability").dump() << ", shift "
            << row.at("errors").at("effective_solid_size").at("shift_in_spacings") << " spacings, t = "
            << row.at("direct_sph").at("time") << "\n";
  return row;
}

void expect_study_band(const json& row) {
  EXPECT_EQ(row.at("status"), "ok") << row.dump();
  const json& e = row.at("errors");
  EXPECT_GT(e.at("permeability").at("relative_difference").get<double>(), 0.0);  // the offset makes k high
  const double shift = e.at("effective_solid_size").at("shift_in_spacings").get<double>();
  EXPECT_GE(shift, 0.25);
  EXPECT_LE(shift, 0.6);
  EXPECT_LT(e.at("max_displacement_dx").get<double>(), 0.5);
  EXPECT_LT(std::abs(e.at("density_deviation").at("min").get<double>()), 1e-3);
  EXPECT_LT(std::abs(e.at("density_deviation").at("max").get<double>()), 1e-3);
  EXPECT_LT(e.at("flow").at("reynolds_a_u_over_nu").get<double>(), 1e-3);
}

}  // namespace

TEST(CylinderLatticeDirectSph, PermeabilityAtCoarseResolutionSmallRadius) { expect_study_band(run_lattice(0.2)); }

TEST(CylinderLatticeDirectSph, PermeabilityAtCoarseResolutionLargeRadius) { expect_study_band(run_lattice(0.3)); }
