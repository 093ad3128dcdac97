// One generic checker run over every registered deconvolver (DESIGN.md §2): registering a strategy is enough
// to have it tested here. The checks live in strategies/conformance/deconvolver_conformance.* (GoogleTest-free),
// so that a user's project runs the very same checks on its own strategy (examples/custom_deconvolver/).
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "strategies/conformance/deconvolver_conformance.hpp"

using namespace closurelab;

namespace {

std::vector<std::string> deconvolver_names() {
  std::vector<std::string> names;
  for (const auto& e : builtin_registry().deconvolvers.entries()) names.push_back(e.name);
  return names;
}

class DeconvolverConformance : public ::testing::TestWithParam<std::string> {
 protected:
  void expect_conforms(const std::string& check) const {
    const ConformanceReport r = run_deconvolver_conformance(builtin_registry(), GetParam(), check);
    ASSERT_EQ(r.checks.size(), 1u) << check;
    EXPECT_TRUE(r.ok()) << r.to_string();
  }
};

}  // namespace

TEST_P(DeconvolverConformance, SchemaIsCompleteAndDefaultsResolve) { expect_conforms("schema_is_complete_and_defaults_resolve"); }
TEST_P(DeconvolverConformance, FixedSolveIsFiniteConsistentAndRepeatable) {
  expect_conforms("fixed_solve_is_finite_consistent_and_repeatable");
}
TEST_P(DeconvolverConformance, ScanReportsTrueResidualsAndStopsWhenAsked) {
  expect_conforms("scan_reports_true_residuals_and_stops_when_asked");
}
TEST_P(DeconvolverConformance, DiscrepancyPrincipleMeetsTauDeltaOrSaysSo) {
  expect_conforms("discrepancy_principle_meets_tau_delta_or_says_so");
}
TEST_P(DeconvolverConformance, RectangularOperatorIsHandledOrRefusedClearly) {
  expect_conforms("rectangular_operator_is_handled_or_refused_clearly");
}
TEST_P(DeconvolverConformance, BadDataIsAConfigError) { expect_conforms("bad_data_is_a_config_error"); }

TEST_P(DeconvolverConformance, EveryRuleBeatsTheDoNothingAnswerClearly) {
  expect_conforms("every_rule_beats_the_do_nothing_answer_clearly");
}

INSTANTIATE_TEST_SUITE_P(AllRegistered, DeconvolverConformance, ::testing::ValuesIn(deconvolver_names()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

// The library itself: every check runs once, a failing strategy is reported with the check and the reason, and
// an unknown name or check is a ConfigError.
TEST(DeconvolverConformanceLibrary, RunsEveryCheckAndNamesUnknownOnes) {
  const ConformanceReport r = run_deconvolver_conformance(builtin_registry(), "cgls");
  EXPECT_EQ(r.checks, deconvolver_conformance_checks());
  EXPECT_TRUE(r.ok()) << r.to_string();
  EXPECT_NE(r.to_string().find("cgls bad_data_is_a_config_error: ok\n"), std::string::npos) << r.to_string();
  EXPECT_THROW(run_deconvolver_conformance(builtin_registry(), "no_such_method"), ConfigError);
  EXPECT_THROW(run_deconvolver_conformance(builtin_registry(), "cgls", "no_such_check"), ConfigError);
}

TEST(DeconvolverConformanceLibrary, ReportsAStrategyThatBreaksTheContract) {
  // A strategy without the discrepancy rule and whose factory ignores its parameters fails the schema check.
  Registry r;
  register_builtin_strategies(r);
  r.deconvolvers.add({"broken", "", {}}, [](const json&) { return builtin_registry().deconvolvers.create(json{{"name", "cgls"}}, "/m"); });
  const ConformanceReport report = run_deconvolver_conformance(r, "broken");
  EXPECT_FALSE(report.ok());
  bool schema_failed = false, name_failed = false;
  for (const auto& f : report.failures) {
    schema_failed |= f.check == "schema_is_complete_and_defaults_resolve";
    name_failed |= f.check == "fixed_solve_is_finite_consistent_and_repeatable";
  }
  EXPECT_TRUE(schema_failed) << report.to_string();
  EXPECT_TRUE(name_failed) << report.to_string();
  EXPECT_NE(report.to_string().find("FAILED"), std::string::npos);
}
