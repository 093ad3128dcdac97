// Experiment-kind conformance: one tiny cell of every registered experiment kind runs end to end through the
// command line (`closurelab run`), and its row has the runner's keys, every section of the kind's schema echoed
// in its resolved parameters, the kind's own required entries, status ok, and finite numbers only in "errors"
// and "cost" (a NaN would be written as null). The cells are a table keyed by kind name and the test iterates
// over the registry: a new kind without a tiny cell here fails, and so does a cell whose kind is gone.
// reduced_model runs with its direct SPH reference and two transient snapshots, both reached.
// The whole suite takes about 1 s on one core (each cell a few hundredths of a second; measured).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

struct TinyCell {
  std::string base;                   // the spec's "base" object (one cell)
  std::vector<std::string> required;  // JSON pointers into the row that must hold a number (or, ending in '/', an entry)
};

// One tiny cell per experiment kind (a few hundredths of a second each).
const std::map<std::string, TinyCell>& tiny_cells() {
  static const std::map<std::string, TinyCell> cells = {
      {"direct_sph_validation",
       {R"({"scene": {"name": "poiseuille-uniform", "n_y": 16},
            "solver": {"mode": "target_time", "target_time": 0.05}})",
        {"/errors/averaged_vs_averaged_analytic/interior/max_rel", "/errors/averaged_vs_analytic/wall_band/max_rel",
         "/errors/peak_relative_difference", "/cost/steps", "/cost/wall_seconds", "/direct_sph/"}}},
      {"deconvolution_stability",
       {R"({"problem": {"name": "gaussian_averaging", "coarse_count": 32}, "method": {"name": "tikhonov", "rule": "gcv"},
            "noise": 0.01})",
        {"/errors/relative_error", "/errors/best_relative_error", "/errors/ratio_to_best", "/cost/matvecs",
         "/condition_number"}}},
      {"quadrature_convergence",
       {R"({"scene": {"name": "poiseuille-uniform", "n_y": 32}, "quadrature": {"name": "coarse", "stride_y": 2},
            "evaluation": {"repeats": 1}})",
        {"/errors/channel/max_rel", "/errors/interior/max_rel", "/errors/wall_band/max_rel",
         "/cost/exact/pair_forces", "/cost/pair_forces_ratio"}}},
      {"reduced_model",
       {R"({"scene": {"name": "poiseuille-uniform", "n_y": 32},
            "quadrature": {"name": "coarse", "stride_y": 2},
            "solver": {"mode": "target_time", "target_time": 0.05, "scheme": "staggered"},
            "reference": {"direct_sph": true, "solver": {"mode": "target_time", "target_time": 0.05}},
            "transient": {"t_over_tau": [0.001, 0.003]}})",
        {"/errors/vs_analytic/all_nodes/max_rel", "/errors/vs_averaged_analytic/interior/max_rel",
         "/errors/vs_averaged_direct_sph/all_nodes/max_rel", "/errors/vs_averaged_direct_sph/wall_band/max_rel",
         "/errors/vs_averaged_direct_sph/peak_relative_difference",
         "/transient/0/vs_averaged_direct_sph/all_nodes/max_rel", "/transient/1/vs_averaged_direct_sph/all_nodes/max_rel",
         "/cost/steps", "/cost/speed_up", "/cost/direct_sph_wall_seconds", "/cost/reduced_timing/min_seconds",
         "/cost/speed_up_at_median", "/cost/direct_sph_timing/threads", "/direct_sph/", "/reduced_model/"}}},
      {"reduced_model_2d",
       {R"({"scene": {"name": "cellular", "n": 32, "eta_over_l": 0.125},
            "closure": {"deconvolver": {"name": "cgls", "iterations": 5}, "discretization": "coarse_fine"},
            "quadrature": {"name": "coarse", "stride_x": 4, "stride_y": 4},
            "solver": {"mode": "target_time", "target_time": 0.01},
            "reference": {"direct_sph": true, "solver": {"mode": "target_time", "target_time": 0.01}},
            "transient": {"t_over_tau": [0.1, 0.3]}})",
        {"/errors/vs_analytic/all_nodes/max_rel", "/errors/vs_averaged_analytic/fluid_nodes/max_rel",
         "/errors/vs_averaged_direct_sph/all_nodes/max_rel", "/errors/vs_averaged_direct_sph/peak_relative_difference",
         "/errors/direct_sph_vs_averaged_analytic/fluid_nodes/max_rel", "/errors/amplitude/ratio", "/transient/1/amplitude/reduced",
         "/cost/steps", "/cost/speed_up", "/cost/bond_weights", "/cost/reduced_timing/median_seconds",
         "/cost/direct_sph_timing/engine_version", "/fields/direct_average/", "/direct_sph/",
         "/reduced_model/"}}},
      {"reduced_model_2d_force_density",  // the cylinder lattice at n = 32, its direct SPH to a short target time
       {R"({"scene": {"name": "cylinder-lattice", "n": 32, "eta_over_l": 0.125},
            "reference": {"direct_sph": true, "solver": {"mode": "target_time", "target_time": 0.005}}})",
        {"/errors/vs_averaged_direct_sph/all_nodes/max_rel", "/errors/vs_averaged_direct_sph/fluid_nodes/max_rel",
         "/errors/vs_averaged_direct_sph/peak_relative_difference", "/errors/permeability/reduced_vs_direct_sph",
         "/errors/permeability/reduced_vs_reference", "/cost/speed_up", "/cost/free_nodes",
         "/cost/reduced_timing/median_seconds", "/fields/direct_average/", "/fields/reduced/", "/direct_sph/",
         "/reduced_model/"}}},
      {"coarse_continuum_2d",  // the reduced_model_2d cell's scene and reference, the baseline on the same mesh
       {R"({"scene": {"name": "cellular", "n": 32, "eta_over_l": 0.125},
            "solver": {"target_time": 0.01},
            "reference": {"direct_sph": true, "solver": {"mode": "target_time", "target_time": 0.01}},
            "transient": {"t_over_tau": [0.1, 0.3]}})",
        {"/errors/vs_analytic/all_nodes/max_rel", "/errors/vs_averaged_analytic/fluid_nodes/max_rel",
         "/errors/vs_averaged_direct_sph/all_nodes/max_rel", "/errors/direct_sph_vs_averaged_analytic/fluid_nodes/max_rel",
         "/errors/amplitude/ratio", "/transient/1/amplitude/baseline", "/cost/steps", "/cost/speed_up",
         "/cost/final_max_divergence", "/cost/reduced_timing/median_seconds", "/fields/direct_average/",
         "/direct_sph/", "/baseline/"}}},
      {"snapshot_closure",  // the file is written by write_inputs() (its path set in the test): the channel's lattice at the analytic flow
       {R"({"scene": {"name": "poiseuille-uniform", "n_y": 32}, "snapshot": {"file": "snapshot.csv"},
            "closure": {"deconvolver": {"name": "landweber", "order": 1}}})",
        {"/errors/stress_xy/channel/max_rel", "/errors/stress_xy/interior/max_rel", "/errors/particle_velocity_max_rel",
         "/cost/deconvolution_seconds"}}},
  };
  return cells;
}

std::vector<std::string> registered_kinds() {
  std::vector<std::string> names;
  for (const ExperimentKind* k : builtin_registry().experiments.all()) names.push_back(k->name());
  return names;
}

// Every number under `j` is finite, and no value is null (how a NaN or an infinity is written); `where` names
// the first offender.
bool all_finite(const json& j, const std::string& path, std::string& where) {
  if (j.is_null()) return where = path + " is null", false;
  if (j.is_number() && !std::isfinite(j.get<double>())) return where = path + " is not finite", false;
  if (j.is_object())
    for (const auto& [k, v] : j.items())
      if (!all_finite(v, path + "/" + k, where)) return false;
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i)
      if (!all_finite(j[i], path + "/" + std::to_string(i), where)) return false;
  return true;
}

// Inputs a kind reads from files, written into the cell's working folder.
void write_inputs(const std::string& kind, const std::filesystem::path& work) {
  if (kind != "snapshot_closure") return;
  const auto scene = builtin_registry().scenes.create(json{{"name", "poiseuille-uniform"}, {"n_y", 32}}, "/scene");
  const ParticleSystem ps = scene->make_particles();
  std::ostringstream csv;
  csv.precision(17);
  csv << "x,y,vx,vy,mass,phase\n";
  for (std::size_t a = 0; a < ps.size(); ++a)
    csv << ps.x[a] << "," << ps.y[a] << "," << (ps.fixed[a] ? 0.0 : scene->analytic_vx(ps.y[a])) << ",0,"
        << ps.mass[a] << "," << ps.phase[a] << "\n";
  write_text(work / "snapshot.csv", csv.str());
}

class EveryKind : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST(EveryKindTable, EachCellNamesARegisteredKind) {
  const auto kinds = registered_kinds();
  EXPECT_GE(kinds.size(), 4u);
  for (const auto& [name, cell] : tiny_cells())
    EXPECT_NE(std::find(kinds.begin(), kinds.end(), name), kinds.end()) << "tiny cell for unknown kind " << name;
}

TEST_P(EveryKind, TinyCellRunsEndToEndWithFiniteErrors) {
  const std::string kind = GetParam();
  const auto it = tiny_cells().find(kind);
  ASSERT_NE(it, tiny_cells().end()) << "experiment kind '" << kind
                                    << "' has no tiny cell: add one to tiny_cells() in " << __FILE__;
  const auto work = fresh_work_folder("every_kind_" + kind);
  json spec = {{"name", "tiny"}, {"kind", kind}, {"base", json::parse(it->second.base)}};
  if (kind == "snapshot_closure") spec["base"]["snapshot"]["file"] = (work / "snapshot.csv").string();
  write_text(work / "tiny.json", spec.dump(2));
  write_inputs(kind, work);
  const CliOutcome o = run_shell(work, "OMP_NUM_THREADS=1 " + std::string(CLOSURELAB_BINARY_DIR) +
                                           "/experiments/closurelab run " + (work / "tiny.json").string() +
                                           " --out " + (work / "out").string());
  ASSERT_EQ(o.code, 0) << o.err;
  const json table = json::parse(read_text(work / "out" / "tiny.json"));
  EXPECT_TRUE(table.at("complete").get<bool>());
  ASSERT_EQ(table.at("rows").size(), 1u);
  const json& row = table["rows"][0];
  ASSERT_EQ(row.value("status", ""), "ok") << row.dump(1).substr(0, 2000);

  // The runner's keys, and every section of the kind's schema resolved into the echoed parameters.
  for (const char* key : {"id", "label", "params", "provenance", "errors", "cost", "status"})
    EXPECT_TRUE(row.contains(key)) << key;
  for (const auto& section : builtin_registry().experiments.get(kind, "/kind").sections()) {
    std::string keys = section.key;  // "a, b, c" lists several top-level keys
    for (std::size_t start = 0; start <= keys.size();) {
      const std::size_t end = std::min(keys.find(", ", start), keys.size());
      const std::string key = keys.substr(start, end - start);
      // reduced_model's "model" is echoed only when the cell names it (a default leaves the cell as the model's kind
      // resolves it, so that committed cell ids stay; experiments/kinds/reduced_model_models.cpp).
      EXPECT_TRUE(row.at("params").contains(key) || key == "model") << "params lacks section '" << key << "'";
      start = end + 2;
    }
  }
  // The kind's own entries: present, and numbers where the pointer names a leaf.
  for (const std::string& p : it->second.required) {
    const bool entry = p.back() == '/';
    const json::json_pointer ptr(entry ? p.substr(0, p.size() - 1) : p);
    ASSERT_TRUE(row.contains(ptr)) << p;
    if (!entry) {
      EXPECT_TRUE(row.at(ptr).is_number()) << p << " = " << row.at(ptr).dump();
    }
  }
  EXPECT_FALSE(row.at("errors").empty());
  for (const char* part : {"errors", "cost"}) {
    std::string where;
    EXPECT_TRUE(all_finite(row.at(part), std::string("/") + part, where)) << where;
  }
  if (row.contains("transient"))
    for (const auto& snap : row.at("transient")) {
      EXPECT_FALSE(snap.contains("status")) << "a snapshot was not reached: " << snap.dump().substr(0, 300);
      std::string where;
      EXPECT_TRUE(all_finite(snap, "/transient", where)) << where;
    }
}

INSTANTIATE_TEST_SUITE_P(Registered, EveryKind, ::testing::ValuesIn(registered_kinds()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });
