// One source for each concept: the solvers' schema defaults are their options' defaults, η' is the scene's,
// and a registry name is registered once.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "core/base/option_table.hpp"
#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/parameter_choice.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/reduced_model.hpp"
#include "experiments/kinds/cell_config.hpp"

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

TEST(SingleSource, TwoDimensionalSolverSchemaDefaultsAreTheOptionsDefaults) {
  const MesoSolver2DOptions d, r = meso_2d_options_from(resolve_params(json::object(), meso_solver_2d_schema(), "/solver"));
  EXPECT_EQ(r.kappa, d.kappa);
  EXPECT_EQ(r.spacing_over_eta, d.spacing_over_eta);
  EXPECT_EQ(r.divergence_order, d.divergence_order);
  EXPECT_EQ(r.equations, d.equations);
  EXPECT_EQ(r.transport, d.transport);
  EXPECT_EQ(r.coarse_pressure, d.coarse_pressure);
  EXPECT_EQ(r.max_time, d.max_time);
  EXPECT_EQ(r.max_steps, d.max_steps);
  EXPECT_EQ(r.steady_window, d.steady_window);
  const ForceDensity2DOptions fd,
      fr = force_density_2d_options_from(resolve_params(json::object(), force_density_2d_schema(), "/solver"));
  EXPECT_EQ(fr.spacing_over_eta, fd.spacing_over_eta);
  EXPECT_EQ(fr.reconstruction_refinement, fd.reconstruction_refinement);
  EXPECT_EQ(fr.reconstruction_y_nodes, fd.reconstruction_y_nodes);
  EXPECT_EQ(fr.window_cutoff, fd.window_cutoff);
  EXPECT_EQ(fr.hold_fraction, fd.hold_fraction);
  EXPECT_EQ(fr.held_node_value, fd.held_node_value);
  EXPECT_EQ(fr.convective_stress, fd.convective_stress);
  EXPECT_EQ(fr.newton_tolerance, fd.newton_tolerance);
  EXPECT_EQ(fr.newton_max_iterations, fd.newton_max_iterations);
}

// One declaration gives the schema (defaults from the struct, in declaration order, enum choices from the name
// table) and the reader (every value read back, an enum by name, a check run after the reads).
struct TableProbe {
  double a = 0.5;
  int n = 3;
  bool on = true;
  MesoScheme scheme = MesoScheme::staggered;
};

TEST(SingleSource, AnOptionTableGivesTheSchemaAndTheReaderFromOneDeclaration) {
  const auto table = OptionTable<TableProbe>("/solver")
                         .number("a", &TableProbe::a, "a number", 0.0, 1.0)
                         .integer("n", &TableProbe::n, "an integer", 1, 9)
                         .boolean("on", &TableProbe::on, "a flag")
                         .choice("scheme", &TableProbe::scheme, "an enumeration")
                         .unbound(string_param("other", "x", "read by its user"))
                         .check([](const TableProbe& o) {
                           if (o.n == 7) throw ConfigError("/solver/n", "not 7");
                         });
  const ParamSchema schema = table.schema();
  ASSERT_EQ(schema.size(), 5u);
  EXPECT_EQ(schema[0].name, "a");
  EXPECT_EQ(schema[0].default_value, 0.5);
  EXPECT_EQ(schema[1].default_value, 3);
  EXPECT_EQ(schema[1].type, ParamType::Integer);
  EXPECT_EQ(schema[2].default_value, true);
  EXPECT_EQ(schema[3].default_value, "staggered");
  EXPECT_EQ(schema[3].choices, names_of<MesoScheme>());
  EXPECT_EQ(schema[4].name, "other");
  const TableProbe r = table.read(resolve_params(json{{"a", 0.25}, {"n", 5}, {"on", false}, {"scheme", "paper"}},
                                                 schema, "/solver"));
  EXPECT_EQ(r.a, 0.25);
  EXPECT_EQ(r.n, 5);
  EXPECT_FALSE(r.on);
  EXPECT_EQ(r.scheme, MesoScheme::paper);
  // Outside the range: the schema refuses it; the check runs on what was read.
  EXPECT_THROW(resolve_params(json{{"n", 10}}, schema, "/solver"), ConfigError);
  try {
    table.read(resolve_params(json{{"n", 7}}, schema, "/solver"));
    FAIL() << "the check did not run";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/solver/n");
  }
  // An enum name the reader meets unresolved is a ConfigError at the option's path.
  json bad = resolve_params(json::object(), schema, "/solver");
  bad["scheme"] = "no_such_scheme";
  try {
    table.read(bad);
    FAIL() << "an unknown name was read";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/solver/scheme");
  }
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
