// One name for the averaging width on every scene: a spec sweeping `scene.eta_over_l` runs, unchanged but for its
// base scene, on a channel and on the cylinder lattice through the command line (the reduced model with solids and
// walls, small sizes, no direct SPH), and each row echoes the width it ran at. The channels' and kolmogorov's earlier
// name, eta_over_ly, still reads as eta_over_l (and is refused beside it), and a stored row that says eta_over_ly
// upgrades to eta_over_l, so committed specs keep their cells and stored rows still match them.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

// The spec both scenes run: only "base.scene" differs.
json sweep_spec(const json& scene) {
  return {{"name", "eta_sweep"},
          {"kind", "reduced_model"},
          {"base",
           {{"model", "force_density_2d"},
            {"scene", scene},
            {"closure", {{"deconvolver", {{"name", "tikhonov"}, {"alpha", 1e-6}}}}},
            {"reference", {{"direct_sph", false}}},
            {"timing", {{"min_repeats", 1}, {"max_repeats", 1}}}}},
          {"axes", {{"scene.eta_over_l", {0.0625, 0.08}}}}};
}

}  // namespace

TEST(EtaOverLEveryScene, OneSpecSweepingEtaOverLRunsOnAChannelAndOnTheCylinderLattice) {
  for (const json& scene : {json{{"name", "poiseuille-uniform"}, {"n_y", 48}}, json{{"name", "cylinder-lattice"}, {"n", 32}}}) {
    const std::string name = scene.at("name").get<std::string>();
    const auto work = fresh_work_folder("eta_over_l_" + name);
    write_text(work / "eta_sweep.json", sweep_spec(scene).dump(2));
    const CliOutcome o = run_shell(work, "OMP_NUM_THREADS=1 " + std::string(CLOSURELAB_BINARY_DIR) +
                                             "/experiments/closurelab run " + (work / "eta_sweep.json").string() +
                                             " --out " + (work / "out").string());
    ASSERT_EQ(o.code, 0) << name << ": " << o.err;
    const json table = json::parse(read_text(work / "out" / "eta_sweep.json"));
    ASSERT_EQ(table.at("rows").size(), 2u) << name;
    std::vector<int> nodes;
    for (std::size_t i = 0; i < 2; ++i) {
      const json& row = table["rows"][i];
      ASSERT_EQ(row.value("status", ""), "ok") << name << ": " << row.dump().substr(0, 1000);
      EXPECT_EQ(row.at("params").at("scene").at("name"), name);
      EXPECT_DOUBLE_EQ(row.at("params").at("scene").at("eta_over_l").get<double>(), i == 0 ? 0.0625 : 0.08) << name;
      EXPECT_FALSE(row.at("params").at("scene").contains("eta_over_ly")) << name;
      nodes.push_back(row.at("cost").at("coarse_nodes").get<int>());
    }
    EXPECT_GT(nodes[0], nodes[1]) << name << ": the wider average has the coarser mesh (the width took effect)";
  }
}

TEST(EtaOverLEveryScene, TheEarlierNameReadsAsEtaOverLAndIsRefusedBesideIt) {
  const Registry& reg = builtin_registry();
  for (const char* scene : {"poiseuille-uniform", "poiseuille-periodic", "kolmogorov"}) {
    const json by_old = reg.scenes.resolve(json{{"name", scene}, {"eta_over_ly", 0.1}}, "/scene");
    const json by_new = reg.scenes.resolve(json{{"name", scene}, {"eta_over_l", 0.1}}, "/scene");
    EXPECT_EQ(by_old, by_new) << scene;
    EXPECT_DOUBLE_EQ(by_new.at("eta_over_l").get<double>(), 0.1) << scene;
    EXPECT_FALSE(by_new.contains("eta_over_ly")) << scene;
    try {
      reg.scenes.resolve(json{{"name", scene}, {"eta_over_ly", 0.1}, {"eta_over_l", 0.1}}, "/scene");
      ADD_FAILURE() << scene << ": both names accepted";
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.path(), "/scene/eta_over_ly") << scene;
    }
  }
  // The scenes that always said eta_over_l read the earlier name too: a sweep written either way carries over.
  EXPECT_EQ(reg.scenes.resolve(json{{"name", "cylinder-lattice"}, {"eta_over_ly", 0.1}}, "/scene").at("eta_over_l"), 0.1);
}

TEST(EtaOverLEveryScene, AStoredRowThatSaysEtaOverLyUpgradesToTheResolvedCell) {
  const Registry& reg = builtin_registry();
  const ExperimentKind& kind = reg.experiments.get("reduced_model", "/kind");
  const json cell = {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 32}, {"eta_over_ly", 0.0625}}},
                     {"quadrature", {{"name", "coarse"}, {"stride_y", 2}}}};
  const json resolved = kind.resolve(cell, "", reg);
  json stored = resolved;
  stored["scene"].erase("eta_over_l");
  stored["scene"]["eta_over_ly"] = 0.0625;  // as the rows stored before the rename say it
  EXPECT_EQ(kind.upgraded_params(stored), resolved);
  EXPECT_EQ(upgraded_scene_params(json{{"name", "kolmogorov"}, {"eta_over_ly", 0.1}}),
            (json{{"name", "kolmogorov"}, {"eta_over_l", 0.1}}));
}
