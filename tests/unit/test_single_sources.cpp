// One source for each concept: the solvers' schema defaults are their options' defaults, η' is the scene's,
// and a registry name is registered once.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/parameter_choice.hpp"
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
  EXPECT_EQ(r.max_steps, d.max_steps);
  EXPECT_EQ(r.wall_constraint_forces, d.wall_constraint_forces);
  EXPECT_EQ(r.wall_node_value, d.wall_node_value);
  EXPECT_EQ(r.balance, d.balance);
}

// Every enumeration's name table round-trips, and an unknown name is a ConfigError listing the choices.
template <class E>
void expect_names_round_trip() {
  for (const std::string& name : names_of<E>()) EXPECT_EQ(name_of(parse_name<E>(name, "/x")), name);
  try {
    parse_name<E>("no_such_choice", "/x");
    ADD_FAILURE() << "unknown name accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/x");
    EXPECT_NE(std::string(e.what()).find(names_of<E>().front()), std::string::npos) << e.what();
  }
}

TEST(SingleSource, EveryEnumerationHasOneNameTable) {
  expect_names_round_trip<Status>();
  expect_names_round_trip<Discretization>();
  expect_names_round_trip<OperatorStorage>();
  expect_names_round_trip<ParameterRule>();
  expect_names_round_trip<WallModel>();
  expect_names_round_trip<PairViscosityMean>();
  expect_names_round_trip<SmoothingKernel::Type>();
  expect_names_round_trip<MesoScheme>();
  expect_names_round_trip<MesoBalance>();
  expect_names_round_trip<WallNodeValue>();
  expect_names_round_trip<BoundaryOracle>();
  EXPECT_EQ(row_status(Status::target_time), "ok");
  EXPECT_EQ(row_status(Status::no_convergence), "no_convergence");
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
