// The two-pass rule (experiments/kinds/reduced_model.cpp): under backward Euler a deconvolver with a parameter rule
// runs to steady state at its configured fixed parameter, the rule picks the parameter once from that steady data,
// and the second pass runs with it fixed. Checked end to end through the CLI on a small near-wall channel: the row
// records the choice, and a run with that parameter fixed from the start gives the same velocities to the bit.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/params.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

json near_wall_channel(const json& deconvolver) {
  return {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 32}}},
          {"closure", {{"deconvolver", deconvolver}, {"discretization", "coarse_fine"}}},
          {"quadrature", {{"name", "coarse"}, {"stride_y", 2}}},
          {"solver",
           {{"mode", "steady"}, {"scheme", "staggered"}, {"balance", "force_density"},
            {"time_integration", "backward_euler"}, {"wall_node_value", "reconstructed"}}},
          {"reference", {{"direct_sph", false}}},
          {"timing", {{"min_repeats", 1}, {"max_repeats", 1}}}};
}

json run_one(const std::string& name, const json& base) {
  const auto work = fresh_work_folder(name);
  write_text(work / "spec.json", json{{"name", "spec"}, {"kind", "reduced_model"}, {"base", base}}.dump(2));
  const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, 0) << o.err;
  return json::parse(read_text(work / "out" / "spec.json")).at("rows").at(0);
}

}  // namespace

TEST(TwoPassRule, GcvUnderBackwardEulerChoosesOnceAndTheSecondPassIsTheFixedRun) {
  const json rule = run_one("two_pass_gcv", near_wall_channel({{"name", "tikhonov"}, {"rule", "gcv"}}));
  ASSERT_EQ(rule.value("status", ""), "ok") << rule.dump(1).substr(0, 1500);
  const json& choice = rule.at("reduced_model").at("two_pass_rule");
  EXPECT_EQ(choice.at("rule"), "gcv");
  EXPECT_EQ(choice.at("parameter"), "alpha");
  EXPECT_EQ(choice.at("pass_1_status"), "ok");
  EXPECT_EQ(choice.at("rule_status"), "ok");
  const double alpha = choice.at("chosen").get<double>();
  ASSERT_TRUE(std::isfinite(alpha) && alpha > 0.0) << alpha;
  EXPECT_NE(alpha, choice.at("pass_1_parameter").get<double>());  // the rule moved it from the configured 1e-6
  EXPECT_FALSE(choice.contains("rule_note")) << choice.at("rule_note");  // chosen inside its scan
  EXPECT_FALSE(rule.contains("note")) << rule.at("note");

  const json fixed = run_one("two_pass_fixed", near_wall_channel({{"name", "tikhonov"}, {"alpha", alpha}}));
  ASSERT_EQ(fixed.value("status", ""), "ok");
  EXPECT_FALSE(fixed.at("reduced_model").contains("two_pass_rule"));
  EXPECT_EQ(rule.at("profile").at("reduced"), fixed.at("profile").at("reduced"));
}

TEST(TwoPassRule, AChoiceAtTheEdgeOfTheScanIsNotedInTheRow) {
  // A scan of [0.1, 1] ||A||^2 lies far above GCV's choice on smooth steady data: it chooses the least regularized
  // member, alpha_min; the row stays ok and says so in its note.
  const json row = run_one("two_pass_gcv_edge",
                           near_wall_channel({{"name", "tikhonov"}, {"rule", "gcv"}, {"alpha_min", 0.1},
                                              {"alpha_max", 1.0}, {"alpha_count", 3}}));
  ASSERT_EQ(row.value("status", ""), "ok") << row.dump(1).substr(0, 1500);
  const json& choice = row.at("reduced_model").at("two_pass_rule");
  EXPECT_EQ(choice.at("rule_status"), "ok");
  ASSERT_TRUE(choice.contains("rule_note")) << choice.dump(1);
  const std::string note = choice.at("rule_note").get<std::string>();
  EXPECT_NE(note.find("at the edge of its scan"), std::string::npos) << note;
  EXPECT_NE(note.find("(the least regularized member scanned)"), std::string::npos) << note;
  EXPECT_NE(note.find("widen the scan"), std::string::npos) << note;
  ASSERT_TRUE(row.contains("note")) << row.dump(1).substr(0, 1500);
  EXPECT_EQ(row.at("note").get<std::string>(), "the two-pass rule: " + note);
}

TEST(TwoPassRule, KrylovClosuresStayRefusedUnderBackwardEuler) {
  const auto work = fresh_work_folder("two_pass_cgls");
  write_text(work / "spec.json",
             json{{"name", "spec"}, {"kind", "reduced_model"}, {"base", near_wall_channel({{"name", "cgls"}})}}.dump(2));
  const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("/base/solver/time_integration"), std::string::npos) << o.err;
}

TEST(TwoPassRule, TheForceDensity2DModelChoosesEachDeconvolversParameterOnce) {
  const auto work = fresh_work_folder("two_pass_cylinders");
  const json base = {{"scene", {{"name", "cylinder-lattice"}, {"n", 32}, {"eta_over_l", 0.125}}},
                     {"closure", {{"deconvolver", {{"name", "tikhonov"}, {"rule", "gcv"}}}}},
                     {"reference", {{"direct_sph", false}}},
                     {"timing", {{"min_repeats", 1}, {"max_repeats", 1}}}};
  write_text(work / "spec.json",
             json{{"name", "spec"}, {"kind", "reduced_model_2d_force_density"}, {"base", base}}.dump(2));
  const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  ASSERT_EQ(o.code, 0) << o.err;
  const json row = json::parse(read_text(work / "out" / "spec.json")).at("rows").at(0);
  ASSERT_EQ(row.value("status", ""), "ok") << row.dump(1).substr(0, 1500);
  const json& choice = row.at("reduced_model").at("two_pass_rule");
  EXPECT_EQ(choice.at("pass_1_status"), "ok");
  for (const char* what : {"velocity", "density"}) {
    const double alpha = choice.at(what).at("chosen").get<double>();
    EXPECT_TRUE(std::isfinite(alpha) && alpha > 0.0) << what << " " << alpha;
    EXPECT_EQ(choice.at(what).at("rule_status"), "ok") << what;
  }
}
