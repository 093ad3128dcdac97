// The 2D force-density model's convective flux (solver.convective_stress, core/reduced/force_density_2d.hpp) on a small
// cylinder lattice (n = 32, η' = L/8): the assembled flux against an independent evaluation, the time derivative of
// the averaged momentum (2.9) of core/averaging as the particles move with their velocities (a central difference);
// then the steady state by Newton: the rates vanish there, Newton converges quadratically, the flux changes nothing
// in Stokes flow and lowers the permeability at Re ~ 1; and the bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "tests/support/force_density_setup.hpp"

using namespace closurelab;

namespace {

using Lattice = closurelab::test_support::ForceDensitySetup;
using closurelab::test_support::random_field;

Lattice make_setup(double g) { return closurelab::test_support::cylinder_lattice_setup(json{{"g", g}}); }

ForceDensity2DOptions options(const json& solver) { return closurelab::test_support::force_density_options(solver); }

double max_abs(const Eigen::VectorXd& v) { return v.cwiseAbs().maxCoeff(); }

double permeability(const Scene& scene, const ForceDensity2DResult& r) {
  return scene.phase_viscosity[0] * r.superficial_velocity / (scene.rho0 * scene.permeability->body_force);
}

}  // namespace

TEST(ForceDensityConvective, FluxIsTheRateOfTheAveragedMomentumAsTheParticlesMove) {
  // d/dt Σ_a m V_a ψ(x − q_a − t V_a) at t = 0, V fixed, is Σ_a m V_a (V_a · ∇_q ψ): the averaged momentum of
  // core/averaging at q ± h V (the fluid particles moved, the solid at rest), a central difference, over ρ̄.
  Lattice s = make_setup(0.01);
  ForceDensitySolver2D solver(*s.scene, *s.kernel, *s.dv, *s.dn, options({{"convective_stress", true}}));
  const Eigen::Index nr = solver.reconstruction_mesh().size();
  const Eigen::VectorXd rx = random_field(nr, 7), ry = random_field(nr, 8);
  const Eigen::VectorXd vx = solver.interpolate_to_particles(rx), vy = solver.interpolate_to_particles(ry);
  const double h = 1e-5 * s.scene->dx;
  const auto momentum_at = [&](double step) {
    ParticleSystem ps = s.scene->make_particles();
    for (std::size_t a = 0; a < ps.size(); ++a)
      if (!ps.fixed[a]) {
        const auto k = static_cast<Eigen::Index>(a);
        ps.vx[a] = vx[k], ps.vy[a] = vy[k];
        ps.x[a] += step * vx[k], ps.y[a] += step * vy[k];
      }
    return average_particles(ps, s.scene->box, *s.kernel, solver.coarse_mesh(), AveragingRequest{});
  };
  const MesoFields plus = momentum_at(h), minus = momentum_at(-h), rest = momentum_at(0.0);
  const Eigen::VectorXd ref_x = (plus.mom_x - minus.mom_x).cwiseQuotient(2.0 * h * rest.rho);
  const Eigen::VectorXd ref_y = (plus.mom_y - minus.mom_y).cwiseQuotient(2.0 * h * rest.rho);
  Eigen::VectorXd qx, qy;
  solver.convective_rates(rx, ry, qx, qy);
  // O(h²) of the difference (h = 1e-5 ε'), round-off over h, and the window's cut at 1e-10 ψ(0).
  EXPECT_LT(max_abs(qx - ref_x), 1e-6 * max_abs(ref_x));
  EXPECT_LT(max_abs(qy - ref_y), 1e-6 * max_abs(ref_y));
  EXPECT_GT(max_abs(ref_x), 0.0);
  std::printf("flux against the momentum's rate: %.2e (x), %.2e (y) of its largest\n",
              max_abs(qx - ref_x) / max_abs(ref_x), max_abs(qy - ref_y) / max_abs(ref_y));
}

TEST(ForceDensityConvective, NewtonReachesAStateWhereEveryRateVanishes) {
  // g = 150: Re = a⟨u⟩/ν ~ 1 on this lattice.
  Lattice s = make_setup(150.0);
  ForceDensitySolver2D solver(*s.scene, *s.kernel, *s.dv, *s.dn, options({{"convective_stress", true}}));
  const ForceDensity2DResult r = solver.run();
  ASSERT_EQ(r.status, Status::converged) << r.message;
  // Quadratic convergence from the Stokes solution: a handful of steps to 1e-10 (an inexact Jacobian would take
  // tens at this Re, or stall).
  EXPECT_LE(r.newton_iterations, 8);
  EXPECT_LE(r.newton_last_step, 1e-10);
  solver.set_state(r.vx, r.vy, r.density);
  Eigen::VectorXd ax, ay, an;
  std::string issue;
  ASSERT_TRUE(solver.rate(ax, ay, an, issue)) << issue;
  const double force = max_abs(solver.averaged_body_force_x());
  EXPECT_LT(max_abs(ax), 1e-8 * force);
  EXPECT_LT(max_abs(ay), 1e-8 * force);
  std::printf("Newton: %ld steps, last %.1e; rates %.1e, %.1e of the force\n", r.newton_iterations, r.newton_last_step,
              max_abs(ax) / force, max_abs(ay) / force);
}

TEST(ForceDensityConvective, NothingChangesInStokesFlowAndInertiaLowersThePermeability) {
  const auto k_of = [](double g, bool convective) {
    Lattice s = make_setup(g);
    ForceDensitySolver2D solver(*s.scene, *s.kernel, *s.dv, *s.dn, options({{"convective_stress", convective}}));
    const ForceDensity2DResult r = solver.run();
    EXPECT_EQ(r.status, Status::converged) << r.message;
    return permeability(*s.scene, r);
  };
  // Re ~ 7e-5: the flux is O(Re) of the viscous force, and the symmetry of the square array makes k's change O(Re²).
  const double stokes = k_of(0.01, true) / k_of(0.01, false);
  EXPECT_NEAR(stokes, 1.0, 1e-6);
  // Re ~ 1: inertia lowers k by about a percent on an ordered array (PySPH's lattice_cylinders.py, the peer:
  // 0.59 % between Re 0.1 and 1 at nx = 96, results/peer/cylinders; this model 0.92 % at n = 96,
  // results/cylinders/reduced_re1): between 0.1 % and 5 % here. A flux of the wrong sign raises k; one missing a
  // factor of the velocity (linear, not quadratic) leaves it at the Stokes value by the array's symmetry.
  const double ratio = k_of(150.0, true) / k_of(150.0, false);
  EXPECT_LT(ratio, 0.999) << ratio;
  EXPECT_GT(ratio, 0.95) << ratio;
  std::printf("k with the flux / without: %.9f at Re ~ 7e-5, %.5f at Re ~ 1\n", stokes, ratio);
}

TEST(ForceDensityConvective, AnXInvariantSceneIsRefusedAtTheOption) {
  const Registry& reg = builtin_registry();
  const auto channel = reg.scenes.create(reg.scenes.resolve(json{{"name", "poiseuille-uniform"}}, "/scene"), "/scene");
  const auto k = reg.kernels.create(json{{"name", "gaussian"}, {"eta", channel->eta}}, "/kernel");
  try {
    check_force_density_2d(*channel, *k, options({{"convective_stress", true}}));
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/solver/convective_stress");
  }
}
