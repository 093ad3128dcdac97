// One source for each concept: the solvers' schema defaults are their options' defaults, η' is the scene's,
// and a registry name is registered once.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/reduced_model.hpp"
#include "experiments/runner/cell_config.hpp"

using namespace closurelab;

TEST(SingleSource, DirectSolverSchemaDefaultsAreTheOptionsDefaults) {
  const SphRunOptions d, r = sph_run_options_from(resolve_params(json::object(), sph_solver_schema(), "/solver"));
  EXPECT_EQ(r.kappa, d.kappa);
  EXPECT_EQ(r.to_steady_state, d.to_steady_state);
  EXPECT_EQ(r.target_time, d.target_time);
  EXPECT_EQ(r.steady_tolerance, d.steady_tolerance);
  EXPECT_EQ(r.steady_window, d.steady_window);
  EXPECT_EQ(r.max_time, d.max_time);
  EXPECT_EQ(r.max_steps, d.max_steps);
}

TEST(SingleSource, ReducedSolverSchemaDefaultsAreTheOptionsDefaults) {
  const MesoSolverOptions d, r = meso_options_from(resolve_params(json::object(), meso_solver_schema(), "/solver"));
  EXPECT_EQ(r.kappa, d.kappa);
  EXPECT_EQ(r.spacing_over_eta, d.spacing_over_eta);
  EXPECT_EQ(r.scheme, d.scheme);
  EXPECT_EQ(r.to_steady_state, d.to_steady_state);
  EXPECT_EQ(r.target_time, d.target_time);
  EXPECT_EQ(r.steady_tolerance, d.steady_tolerance);
  EXPECT_EQ(r.steady_window, d.steady_window);
  EXPECT_EQ(r.max_time, d.max_time);
  EXPECT_EQ(r.wall_constraint_forces, d.wall_constraint_forces);
  EXPECT_EQ(r.wall_node_value, d.wall_node_value);
  EXPECT_EQ(r.balance, d.balance);
  EXPECT_EQ(r.time_integration, d.time_integration);
}

TEST(SingleSource, AKernelEtaThatDiffersFromTheScenesIsRejectedAtItsPath) {
  const Registry& reg = builtin_registry();
  const json cell = {{"kernel", {{"name", "gaussian"}, {"eta", 0.04}}}};
  try {
    build_kernel(cell, "/cells/0", reg, 0.0625, nullptr);
    FAIL() << "a conflicting eta was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/cells/0/kernel/eta");
  }
  // Repeating the scene's value, or leaving it out, gives the scene's η'.
  json resolved;
  EXPECT_DOUBLE_EQ(build_kernel({{"kernel", {{"name", "gaussian"}, {"eta", 0.0625}}}}, "", reg, 0.0625, nullptr)->eta(), 0.0625);
  EXPECT_DOUBLE_EQ(build_kernel({{"kernel", "cutoff_gaussian"}}, "", reg, 0.05, &resolved)->eta(), 0.05);
  EXPECT_DOUBLE_EQ(resolved.at("eta").get<double>(), 0.05);
}

TEST(SingleSource, ARegistryNameIsRegisteredOnce) {
  Registry r;
  register_builtin_strategies(r);
  register_builtin_strategies(r);  // idempotent
  const EntryInfo info = r.deconvolvers.info("landweber");
  EXPECT_THROW(r.deconvolvers.add(info, [](const json&) { return std::unique_ptr<Deconvolver>(); }), std::logic_error);
}
