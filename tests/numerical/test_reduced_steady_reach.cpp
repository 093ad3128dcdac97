// The reduced models' own run control is checked at validation as the direct SPH's is: a steady test
// whose window cannot see the scene's slowest relaxation at the coarse step is refused (check_steady_reach at
// the coarse spacing), and a target_time beyond max_steps is refused (check_steps_reach_target). The refusal is
// earned: the reduced kolmogorov model with such a window stops "converged" more than kMaxSteadyDistance from
// its steady state.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"
#include "tests/support/config_error.hpp"

using namespace closurelab;
using closurelab::test_support::config_error;

namespace {

json solver_1d(const json& set) {
  json s = resolve_params(set, meso_solver_schema(), "/solver");
  return s;
}

struct Kolmogorov {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<AveragingKernel> kernel;
};

// k = 1 (q = 2 pi), eta' = L/16, coarse spacing eta'/2 = L/32: the sine mode relaxes like a channel of width
// pi/q = 16 coarse spacings.
Kolmogorov kolmogorov() {
  const Registry& reg = builtin_registry();
  Kolmogorov k{reg.scenes.create(json{{"name", "kolmogorov"}, {"n_y", 64}, {"k", 1}, {"eta_over_ly", 1.0 / 16}}, "/scene"),
               nullptr};
  k.kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", k.scene->eta}}, "/kernel");
  return k;
}

MesoResult run(const Kolmogorov& k, const json& solver) {
  const Registry& reg = builtin_registry();
  auto deconv = reg.deconvolvers.create(json{{"name", "landweber"}, {"order", 1}}, "/deconvolver");
  auto quad = reg.quadratures.create(json{{"name", "exact"}}, "/quadrature");
  auto integrator = make_integrator(reg, solver, "");
  MesoSolver s(*k.scene, *k.kernel, *deconv, *quad, *integrator, meso_options_from(solver));
  return s.run();
}

}  // namespace

TEST(SteadyReach, EachSceneStatesItsSlowestRelaxationAsAChannelWidth) {
  const Registry& reg = builtin_registry();
  const auto channel = reg.scenes.create(json{{"name", "poiseuille-uniform"}, {"n_y", 32}}, "/scene");
  EXPECT_DOUBLE_EQ(steady_reach_spacings(*channel, 0.1), (channel->wall_hi - channel->wall_lo) / 0.1);
  const Kolmogorov k = kolmogorov();
  EXPECT_NEAR(steady_reach_spacings(*k.scene, 1.0 / 32), 16.0, 1e-12);  // pi / (2 pi) / (1/32)
  const auto cell = reg.scenes.create(json{{"name", "cellular"}, {"n", 32}}, "/scene");
  // Rate 2 k^2 nu, k = 2 pi: W = pi / (sqrt 2 k) = 1 / (2 sqrt 2).
  EXPECT_NEAR(steady_reach_spacings(*cell, 0.125), 1.0 / (2 * std::sqrt(2.0) * 0.125), 1e-12);
  EXPECT_NEAR(std::numbers::pi * std::numbers::pi / std::pow(steady_reach_spacings(*cell, 1.0), 2),
              cell->cellular_mode->decay_rate * cell->rho0 / cell->max_viscosity(), 1e-9);
  const auto cylinder = reg.scenes.create(json{{"name", "cylinder-lattice"}}, "/scene");
  EXPECT_EQ(steady_reach_spacings(*cylinder, 0.1), 0.0);  // no relaxation stated: no check
}

TEST(SteadyReach, AReducedWindowTheCoarseStepCannotFillIsRefusedAndWouldStopFarFromSteady) {
  const Kolmogorov k = kolmogorov();
  const json short_window =
      solver_1d({{"spacing_over_eta", 0.5}, {"kappa", 0.25}, {"steady_window", 4}, {"steady_tolerance", 1e-3}});
  const MesoSolverOptions o = meso_options_from(short_window);
  const std::string e = config_error([&] { check_meso_run(*k.scene, *k.kernel, short_window, o, "/solver"); });
  EXPECT_NE(e.find("/solver/steady_window"), std::string::npos) << e;
  EXPECT_NE(e.find("from steady state"), std::string::npos) << e;
  // Run anyway (bypassing validation): "converged", and far from the steady state of a long target_time run
  // (e^{-12} of the start-up left).
  const MesoResult stopped = run(k, short_window);
  ASSERT_EQ(stopped.status, Status::converged) << stopped.message;
  json long_run = short_window;
  long_run["mode"] = "target_time";
  long_run["target_time"] = 12.0 / (4 * std::numbers::pi * std::numbers::pi);  // 12 tau, tau = 1 / (q^2 nu)
  EXPECT_NO_THROW(check_meso_run(*k.scene, *k.kernel, long_run, meso_options_from(long_run), "/solver"));
  const MesoResult steady = run(k, long_run);
  ASSERT_EQ(steady.status, Status::target_time) << steady.message;
  const double distance =
      (stopped.v - steady.v).cwiseAbs().maxCoeff() / steady.v.cwiseAbs().maxCoeff();
  std::printf("short window stopped %.3g %% from steady (bound %.3g %%)\n", 100 * distance,
              100 * steady_distance_bound(short_window, 16.0));
  EXPECT_GT(distance, kMaxSteadyDistance);
  // The committed specs' window (1000 steps, tolerance 1e-5) passes.
  const json committed = solver_1d({{"spacing_over_eta", 0.5}, {"steady_window", 1000}, {"steady_tolerance", 1e-5}});
  EXPECT_NO_THROW(check_meso_run(*k.scene, *k.kernel, committed, meso_options_from(committed), "/solver"));
}

TEST(SteadyReach, AReducedTargetTimeBeyondMaxStepsIsRefused) {
  const Kolmogorov k = kolmogorov();
  // Steps of at most kappa rho h^2 / mu = 0.25 / 32^2: 1 model time needs 4096 steps.
  json s = solver_1d({{"spacing_over_eta", 0.5}, {"mode", "target_time"}, {"target_time", 1.0}, {"max_steps", 4000}});
  const std::string e = config_error([&] { check_meso_run(*k.scene, *k.kernel, s, meso_options_from(s), "/solver"); });
  EXPECT_NE(e.find("/solver/target_time"), std::string::npos) << e;
  EXPECT_NE(e.find("4096"), std::string::npos) << e;
  s["max_steps"] = 4097;
  EXPECT_NO_THROW(check_meso_run(*k.scene, *k.kernel, s, meso_options_from(s), "/solver"));
}

TEST(SteadyReach, The2DModelIsCheckedAtItsCoarseSpacing) {
  const Registry& reg = builtin_registry();
  const auto cell = reg.scenes.create(json{{"name", "cellular"}, {"n", 48}}, "/scene");
  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", cell->eta}}, "/kernel");
  json s = resolve_params(json{{"kappa", 0.25}, {"steady_window", 4}, {"steady_tolerance", 5e-3}},
                          meso_solver_2d_schema(), "/solver");
  const std::string e =
      config_error([&] { check_meso_run_2d(*cell, *kernel, s, meso_2d_options_from(s), "/solver"); });
  EXPECT_NE(e.find("/solver/steady_window"), std::string::npos) << e;
  s["steady_tolerance"] = 1e-5;
  EXPECT_NO_THROW(check_meso_run_2d(*cell, *kernel, s, meso_2d_options_from(s), "/solver"));
  s["mode"] = "target_time";
  s["target_time"] = 1e3;
  s["max_time"] = 1e4;
  s["max_steps"] = 100000;  // steps of at most 0.25 (L/16)^2: 1e3 needs 4.1e6
  EXPECT_NE(config_error([&] { check_meso_run_2d(*cell, *kernel, s, meso_2d_options_from(s), "/solver"); })
                .find("/solver/target_time"),
            std::string::npos);
}
