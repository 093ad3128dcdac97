// One kind "reduced_model" for every scene (experiments/kinds/reduced_model_models.cpp): the model chosen by the
// scene or by the cell's "model", validated and run by that model's own kind, a cell without "model" resolving as the
// model's kind resolves it (so committed specs keep their cell ids); bad model names refused at /model.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "experiments/kinds/experiment_kind.hpp"

using namespace closurelab;

namespace {

const json kCylinders = {{"scene", {{"name", "cylinder-lattice"}, {"n", 32}, {"eta_over_l", 0.125}}},
                         {"closure", {{"deconvolver", {{"name", "tikhonov"}, {"alpha", 1e-6}}}}},
                         {"reference", {{"direct_sph", false}}},
                         {"timing", {{"min_repeats", 1}, {"max_repeats", 1}}}};
const json kChannel = {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 32}}},
                       {"closure", {{"deconvolver", {{"name", "tikhonov"}, {"alpha", 1e-6}}}}},
                       {"reference", {{"direct_sph", false}}},
                       {"timing", {{"min_repeats", 1}, {"max_repeats", 1}}}};

std::string path_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.path();
  }
  return "(no error)";
}

}  // namespace

TEST(ReducedModelModels, TheSceneChoosesTheModelAndTheCellResolvesAsThatKindResolvesIt) {
  const Registry& reg = builtin_registry();
  const ExperimentKind& any = builtin_registry().experiments.get("reduced_model", "");
  const ExperimentKind& fd = builtin_registry().experiments.get("reduced_model_2d_force_density", "");
  const json resolved = any.resolve(kCylinders, "", reg);
  EXPECT_EQ(resolved, fd.resolve(kCylinders, "", reg));
  EXPECT_FALSE(resolved.contains("model"));
  const json a = any.run(resolved, reg, [](const std::string&) {}), b = fd.run(resolved, reg, [](const std::string&) {});
  EXPECT_EQ(a.at("fields").at("reduced"), b.at("fields").at("reduced"));
  EXPECT_EQ(a.at("status"), "ok");
}

TEST(ReducedModelModels, ANamedModelRunsAChannelInTwoDimensionsAndIsKeptInTheCell) {
  const Registry& reg = builtin_registry();
  const ExperimentKind& any = builtin_registry().experiments.get("reduced_model", "");
  json cell = kChannel;
  cell["model"] = "force_density_2d";
  const json resolved = any.resolve(cell, "", reg);
  EXPECT_EQ(resolved.at("model"), "force_density_2d");
  const json row = any.run(resolved, reg, [](const std::string&) {});
  ASSERT_EQ(row.at("status"), "ok") << row.dump();
  EXPECT_EQ(row.at("cost").at("coarse_nodes").get<int>(), row.at("fields").at("y").size());  // one column
  // The default for an x-invariant scene is the 1D column: its own closure section (a discretization) resolves.
  json column = kChannel;
  column["closure"]["discretization"] = "coarse_fine";
  column["solver"] = {{"mode", "steady"}, {"balance", "force_density"}, {"time_integration", "backward_euler"}};
  const json resolved_column = any.resolve(column, "", reg);
  EXPECT_TRUE(resolved_column.at("closure").contains("discretization"));
  EXPECT_TRUE(resolved_column.contains("oracle"));  // the 1D model's sections
  EXPECT_FALSE(resolved_column.contains("model"));
}

TEST(ReducedModelModels, BadModelsAreRefusedAtTheirPath) {
  const Registry& reg = builtin_registry();
  const ExperimentKind& any = builtin_registry().experiments.get("reduced_model", "");
  json cell = kChannel;
  cell["model"] = "spectral";
  EXPECT_EQ(path_of([&] { any.resolve(cell, "/base", reg); }), "/base/model");
  cell["model"] = 2;
  EXPECT_EQ(path_of([&] { any.resolve(cell, "/base", reg); }), "/base/model");
  // A model that cannot serve the scene says so through its own kind: the 1D column on the cylinder lattice.
  json cylinders = kCylinders;
  cylinders["model"] = "column";
  EXPECT_EQ(path_of([&] { any.resolve(cylinders, "/base", reg); }), "/base/scene");
  // The force-density model's solver section is its own: a 1D key is unknown there.
  cell = kChannel;
  cell["model"] = "force_density_2d";
  cell["solver"] = {{"scheme", "staggered"}};
  EXPECT_EQ(path_of([&] { any.resolve(cell, "/base", reg); }), "/base/solver/scheme");
}
