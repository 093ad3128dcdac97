// Direct SPH of Stokes flow through the periodic lattice of cylinders at a coarse resolution (n = 48), through the
// direct_sph_validation kind's permeability path (experiments/kinds/permeability_validation.cpp): steady state by
// the permeability itself, k against the collocation reference, for both committed radii (a = 0.2 L, 0.3 L).
//
// What the resolution study measured (results/cylinders/direct/table.md, n = 48, 96, 192): the zero-velocity solid
// puts the no-slip surface 0.35-0.51 lattice spacings inside the nominal cylinder at every n (the channels' known
// ~eps'/2 offset, DESIGN.md par. 6), so k is high by a first-order error (+8.7 %, +4.1 %, +2.2 % at a = 0.2 L;
// +14.7 %, +4.9 %, +2.6 % at a = 0.3 L). The tests hold the n = 48 runs (shift 0.42 and 0.51) to the band the
// study spans, widened by ~0.1 spacing: shift within [0.25, 0.6] spacings. At n = 48 one spacing of radius moves k
// by ~22 % (a = 0.2 L) and ~24 % (0.3 L), so the band is k within about +-2-4 % of the measured values and fails on
// a lost or doubled offset (a solid whose particles are not held, a missing fluid-solid pair, a wrong reference).
// Also: the particles within half a spacing of their sites (measured 0.010, 0.016) and the density within 1e-3
// (measured 1.2e-4; rho g L / (rho c^2) = 1e-4). Both runs take ~5 s on one core (the test runs them on one thread).
// Then the same with ghost-velocity solids (below).
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>

#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/permeability_validation.hpp"

using namespace closurelab;

namespace {

json run_lattice(double a, const json& solid = json::object()) {
  // One thread: 2304 particles are too few for threads to pay (a parallel region per pass; on the shared 2-core
  // machine two threads made each run 5-10x slower, 20-30 s instead of 2-4 s).
  omp_set_num_threads(1);
  json params = {{"name", "cylinder-lattice"}, {"n", 48}, {"radius_over_length", a}};
  params.update(solid);
  const auto scene = builtin_registry().scenes.create(params, "/scene");
  SphRunOptions opt;
  opt.steady_tolerance = 1e-4;  // as experiments/cylinders/direct.json: the drift after the plateau is ~1e-4 per window
  opt.steady_window = 150;      // 1/60 model time at n = 48 (dt = 0.25 eps'^2 rho / mu)
  opt.max_time = 1.0;
  const json row = run_permeability_validation(*scene, opt);
  std::cout << "a/L = " << a << ": " << row.at("errors").at("permeability").dump() << ", shift "
            << row.at("errors").at("effective_solid_size").at("shift_in_spacings")
            << " spacings, t = " << row.at("direct_sph").at("time") << "\n";
  return row;
}

// k against the reference: the study's n = 48 value (+8.66 % at a = 0.2 L, +14.68 % at 0.3 L) within 3 points,
// i.e. about an eighth of a spacing of effective radius, and ten times both the spread from where the run stops
// (the drift after the plateau, ~0.3 %) and the change from background pressure 0.02 to 0.05 rho c^2 (0.35 %).
void expect_study_band(const json& row, double study_relative_difference) {
  EXPECT_EQ(row.at("status"), "ok") << row.dump();
  const json& e = row.at("errors");
  EXPECT_NEAR(e.at("permeability").at("relative_difference").get<double>(), study_relative_difference, 0.03);
  const double shift = e.at("effective_solid_size").at("shift_in_spacings").get<double>();
  EXPECT_GE(shift, 0.25);
  EXPECT_LE(shift, 0.6);
  EXPECT_LT(e.at("max_displacement_dx").get<double>(), 0.5);
  EXPECT_LT(std::abs(e.at("density_deviation").at("min").get<double>()), 1e-3);
  EXPECT_LT(std::abs(e.at("density_deviation").at("max").get<double>()), 1e-3);
  EXPECT_LT(e.at("flow").at("reynolds_a_u_over_nu").get<double>(), 1e-3);
}

}  // namespace

TEST(CylinderLatticeDirectSph, PermeabilityAtCoarseResolutionSmallRadius) {
  expect_study_band(run_lattice(0.2), 0.0866);
}

TEST(CylinderLatticeDirectSph, PermeabilityAtCoarseResolutionLargeRadius) {
  expect_study_band(run_lattice(0.3), 0.1468);
}

// Ghost-velocity solids (Morris et al. 1997, beta capped at 1.5; experiments/cylinders/direct_ghost.json): the
// velocity continued into the solid vanishes on the nominal surface, so the offset of the no-slip surface shrinks.
// Measured at n = 48 (results/cylinders/direct_ghost): +4.54 % and +7.87 % (shift 0.23 and 0.28 spacings) against
// the zero-velocity solid's +8.66 % and +14.68 % (0.42, 0.51). Held to 2 points (about a tenth of a spacing) and to
// a shift under 0.33 and 0.38 spacings (a tenth above the measured ghost shifts, below the zero-velocity solid's):
// fails on a ghost model that is not applied to the solid (the zero-velocity figures) or that measures the
// distances to the walls in y.
namespace {

void expect_ghost_band(const json& row, double measured_relative_difference, double max_shift) {
  EXPECT_EQ(row.at("status"), "ok") << row.dump();
  const json& e = row.at("errors");
  EXPECT_NEAR(e.at("permeability").at("relative_difference").get<double>(), measured_relative_difference, 0.02);
  EXPECT_LT(e.at("effective_solid_size").at("shift_in_spacings").get<double>(), max_shift);
  EXPECT_LT(e.at("max_displacement_dx").get<double>(), 0.5);
}

const json kGhostSolid = {{"wall_model", "ghost_velocity"}, {"ghost_beta_max", 1.5}};

}  // namespace

TEST(CylinderLatticeDirectSph, GhostVelocitySolidSmallRadius) {
  expect_ghost_band(run_lattice(0.2, kGhostSolid), 0.0454, 0.33);
}

TEST(CylinderLatticeDirectSph, GhostVelocitySolidLargeRadius) {
  expect_ghost_band(run_lattice(0.3, kGhostSolid), 0.0787, 0.38);
}
