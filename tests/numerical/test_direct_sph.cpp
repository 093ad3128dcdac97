// Direct SPH steady profiles against (5.15) and (D.3): order of accuracy in ε' for both wall models,
// the zero-velocity wall's offset (DESIGN.md §6), and steady-state detection.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"

using namespace closurelab;

namespace {

struct Profile {
  double max_rel = 0.0;  // max |v − V| / max V over the fluid particles
  double centre_over = 0.0;  // (max v − max V) / max V
  SphRunResult run;
};

Profile run_channel(const std::string& scene_name, int ny, const std::string& walls, double t_end) {
  const auto scene = builtin_registry().scenes.create(
      json{{"name", scene_name}, {"n_y", ny}, {"wall_model", walls}}, "/scene");
  ParticleSystem ps = scene->make_particles();
  SphRunOptions opt;
  opt.to_steady_state = t_end <= 0.0;
  opt.target_time = t_end;
  opt.max_time = 50.0;
  Profile p;
  p.run = run_direct_sph(*scene, ps, opt);
  double vmax = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    p.max_rel = std::max(p.max_rel, std::abs(ps.vx[a] - scene->analytic_vx(ps.y[a])));
    vmax = std::max(vmax, ps.vx[a]);
  }
  p.max_rel /= scene->analytic_peak;
  p.centre_over = (vmax - scene->analytic_peak) / scene->analytic_peak;
  return p;
}

}  // namespace

// t = 1 is steady to ~e^{−25}: the slowest viscous mode decays like exp(−π² ν t / W²), W = 0.625.
TEST(DirectSph, ZeroVelocityWallsConvergeAtFirstOrderWithTheExpectedOffset) {
  const Profile coarse = run_channel("poiseuille-uniform", 32, "zero_velocity", 1.0);
  const Profile fine = run_channel("poiseuille-uniform", 64, "zero_velocity", 1.0);
  const double order = std::log2(coarse.max_rel / fine.max_rel);
  std::cout << "zero-velocity walls: max rel error " << coarse.max_rel << " (n_y=32), " << fine.max_rel
            << " (n_y=64), order " << order << "\n";
  EXPECT_NEAR(order, 1.0, 0.2);  // the wall offset is O(ε'): first order
  // The centre is overpredicted by about 2ε'/W (W = 0.625: 10 % at n_y = 32, 5 % at n_y = 64).
  EXPECT_NEAR(coarse.centre_over / (2.0 / 32 / 0.625), 1.0, 0.25);
  EXPECT_NEAR(fine.centre_over / (2.0 / 64 / 0.625), 1.0, 0.25);
}

TEST(DirectSph, GhostVelocityWallsAreAccurate) {
  const Profile coarse = run_channel("poiseuille-uniform", 32, "ghost_velocity", 1.0);
  const Profile fine = run_channel("poiseuille-uniform", 64, "ghost_velocity", 1.0);
  const double order = std::log2(coarse.max_rel / fine.max_rel);
  std::cout << "ghost-velocity walls: max rel error " << coarse.max_rel << " (n_y=32), " << fine.max_rel
            << " (n_y=64), order " << order << "\n";
  EXPECT_LT(fine.max_rel, 0.0015);  // measured 0.129 % (0.370 % at n_y = 32)
  EXPECT_GT(order, 1.4);            // measured 1.52 (deterministic; first order, 1.0, must fail)
}

TEST(DirectSph, PeriodicForceMatchesD3) {
  const Profile coarse = run_channel("poiseuille-periodic", 32, "ghost_velocity", 1.0);
  const Profile fine = run_channel("poiseuille-periodic", 64, "ghost_velocity", 1.0);
  std::cout << "periodic force, ghost walls: max rel error " << coarse.max_rel << " (n_y=32), " << fine.max_rel
            << " (n_y=64)\n";
  EXPECT_LT(fine.max_rel, coarse.max_rel);
  EXPECT_LT(fine.max_rel, 0.01);
}

TEST(DirectSph, SteadyStateDetectionAgreesWithALongRun) {
  const Profile steady = run_channel("poiseuille-uniform", 32, "ghost_velocity", 0.0);
  ASSERT_EQ(steady.run.status, Status::converged);
  const Profile long_run = run_channel("poiseuille-uniform", 32, "ghost_velocity", 3.0);
  EXPECT_GT(long_run.run.time, steady.run.time);
  // Converged to 1e-5 per 1000 steps. Lattice rows sliding past each other (and past the wall rows) keep a
  // slow ripple of about ±10 % of the discretization error (measured at n_y = 32: 0.31–0.38 % for
  // t in [0.5, 8]); the steady answer must lie within that band.
  EXPECT_NEAR(steady.max_rel, long_run.max_rel, 0.25 * long_run.max_rel);
}
