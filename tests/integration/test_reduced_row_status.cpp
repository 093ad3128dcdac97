// A reduced row's status is the worst of its parts (experiments/kinds/reduced_sections.hpp,
// propagate_worst_status): a closure whose deconvolutions report numerical issues, or a direct reference that did
// not reach its steady state, does not leave the row "ok".
#include <gtest/gtest.h>

#include "core/base/params.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

json run_row(const std::string& name, const json& base) {
  const auto work = fresh_work_folder(name);
  write_text(work / "spec.json", json{{"name", "spec"}, {"kind", "reduced_model"}, {"base", base}}.dump(2));
  const CliOutcome o = run_shell(work, "OMP_NUM_THREADS=1 CLOSURELAB_STORE=" + (work / "store").string() + " " +
                                           std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab run " +
                                           (work / "spec.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, 0) << o.err;
  return json::parse(read_text(work / "out" / "spec.json")).at("rows").at(0);
}

json channel() {
  return {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 32}}},
          {"quadrature", {{"name", "coarse"}, {"stride_y", 2}}},
          {"solver", {{"mode", "target_time"}, {"target_time", 0.02}, {"scheme", "staggered"}}},
          {"reference", {{"direct_sph", false}}},
          {"timing", {{"min_repeats", 1}, {"max_repeats", 1}}}};
}

}  // namespace

TEST(ReducedRowStatus, AClosureThatFitsNoBetterThanZeroMakesTheRowANumericalIssue) {
  json base = channel();
  base["closure"] = {{"deconvolver", {{"name", "tikhonov"}, {"alpha", 1e300}}}};
  const json row = run_row("row_status_alpha", base);
  EXPECT_EQ(row.at("status"), "numerical_issue") << row.dump(1).substr(0, 1500);
  EXPECT_NE(row.value("message", "").find("deconvolution"), std::string::npos);
  EXPECT_GT(row.at("reduced_model").at("deconvolution_issues").at("solves").get<long>(), 0);
}

TEST(ReducedRowStatus, AReferenceThatDidNotReachSteadyStateMakesTheRowNoConvergence) {
  json base = channel();
  base["reference"] = {{"direct_sph", true},
                       {"solver", {{"mode", "steady"}, {"max_time", 0.002}, {"steady_window", 10}}}};
  const json row = run_row("row_status_reference", base);
  ASSERT_EQ(row.at("direct_sph").at("status"), "no_convergence");
  EXPECT_EQ(row.at("status"), "no_convergence");
  EXPECT_NE(row.value("message", "").find("direct SPH reference"), std::string::npos);
}

TEST(ReducedRowStatus, AHealthyRowStaysOk) {
  const json row = run_row("row_status_ok", channel());
  EXPECT_EQ(row.at("status"), "ok");
  EXPECT_FALSE(row.contains("message"));
}

TEST(ReferenceStoreLocation, WithoutHomeOrCLOSURELAB_STOREARunSaysWhereTheStoreIs) {
  const auto work = fresh_work_folder("store_without_home");
  write_text(work / "spec.json", json{{"name", "spec"}, {"kind", "reduced_model"}, {"base", channel()}}.dump(2));
  const CliOutcome o = run_shell(work, "cd " + work.string() + " && env -u HOME -u CLOSURELAB_STORE OMP_NUM_THREADS=1 " +
                                           std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab run spec.json --out out");
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("neither CLOSURELAB_STORE nor HOME is set"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find(".closurelab-store"), std::string::npos) << o.err;
}

TEST(ReducedRowStatus, StrictExitsThreeWhenARowIsNotOk) {
  // The table is written either way; --strict makes the untrustworthy row visible to a script (exit 3), and a
  // healthy spec still exits 0 with it.
  json base = channel();
  base["closure"] = {{"deconvolver", {{"name", "tikhonov"}, {"alpha", 1e300}}}};
  for (const bool healthy : {false, true}) {
    if (healthy) base["closure"] = {{"deconvolver", {{"name", "landweber"}, {"order", 0}}}};
    const auto work = fresh_work_folder(healthy ? "strict_ok" : "strict_not_ok");
    write_text(work / "spec.json", json{{"name", "spec"}, {"kind", "reduced_model"}, {"base", base}}.dump(2));
    const CliOutcome o = run_shell(work, "OMP_NUM_THREADS=1 CLOSURELAB_STORE=" + (work / "store").string() + " " +
                                             std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab run " +
                                             (work / "spec.json").string() + " --out " + (work / "out").string() +
                                             " --strict");
    EXPECT_EQ(o.code, healthy ? 0 : 3) << o.err;
    EXPECT_TRUE(std::filesystem::exists(work / "out" / "spec.json"));
    if (!healthy) {
      EXPECT_NE(o.err.find("1 not ok"), std::string::npos) << o.err;
    }
  }
}
