// A parameter rule's choice at the edge of its own scan is noted (core/closure/parameter_choice.hpp): GCV, the
// L-curve or the discrepancy principle choosing the first or last member scanned leaves the status as it is but
// fills stats.note ("... at the edge of its scan [lo, hi] ...; widen the scan"), which the rows carry as "note".
// A choice inside the scan has none. Shaw's problem with 1 % noise: the rules' choices lie inside Tikhonov's
// default scan [1e-16, 1] ||A||^2; narrower scans put them outside.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <string>

#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/reduced/meso_solver.hpp"
#include "experiments/testproblems/ill_posed_problems.hpp"
#include "experiments/kinds/reduced_sections.hpp"
#include "experiments/testproblems/stability_case.hpp"

using namespace closurelab;

namespace {

struct Noisy {
  IllPosedProblem p = make_shaw_problem(32);
  Eigen::VectorXd b;
  double delta = 0.0;
  Noisy() { b = add_noise(p.b_exact, 0.01, 12345, delta); }
};

DeconvolutionResult solve(const json& method, const Noisy& n, double delta) {
  auto d = builtin_registry().deconvolvers.create(method, "/method");
  d->setup(n.p.a);
  return d->solve(n.b, delta);
}

bool has(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

const json kSmall = {{"alpha_min", 1e-16}, {"alpha_max", 1e-14}, {"alpha_count", 5}};
const json kAbove = {{"alpha_min", 0.1}, {"alpha_max", 1.0}, {"alpha_count", 5}};

json tikhonov(const std::string& rule, const json& scan = json::object()) {
  json m = {{"name", "tikhonov"}, {"rule", rule}};
  m.update(scan);
  return m;
}

}  // namespace

TEST(ParameterChoiceEdge, RulesInsideTheirScanLeaveNoNote) {
  const Noisy n;
  for (const char* rule : {"gcv", "lcurve", "discrepancy"}) {
    const DeconvolutionResult r = solve(tikhonov(rule), n, n.delta);
    EXPECT_EQ(r.status, DeconvolutionStatus::converged) << rule << ": " << r.stats.message;
    EXPECT_TRUE(r.stats.note.empty()) << rule << ": " << r.stats.note;
    EXPECT_FALSE(r.to_json().at("stats").contains("note")) << rule;
  }
}

TEST(ParameterChoiceEdge, GcvAtEitherEndOfTheScanIsNoted) {
  // (The L-curve's corner is an inner vertex of the curve's lower hull: it reaches an end of the scan only on a
  // curve of fewer than three points.) GCV's choice alpha* in the default scan lies inside it; a scan of
  // [alpha*/100, alpha*/10] lies below it (GCV then chooses its most regularized member), one of [0.1, 1] ||A||^2
  // above it (the least regularized member), and so does [1e-16, 1e-14] ||A||^2, where GCV drifts to the smallest
  // alpha scanned.
  const Noisy n;
  const DeconvolutionResult inside = solve(tikhonov("gcv"), n, n.delta);
  ASSERT_TRUE(inside.stats.note.empty()) << inside.stats.note;
  const double norm2 = std::pow(Eigen::JacobiSVD<Eigen::MatrixXd>(n.p.a.to_dense()).singularValues()(0), 2);
  const double star = inside.stats.chosen_parameter / norm2;  // relative to ||A||^2, as the scan's bounds
  const json below = {{"alpha_min", star / 100}, {"alpha_max", star / 10}, {"alpha_count", 5}};
  for (const json* scan : {&below, &kAbove, &kSmall}) {
    const bool most = scan == &below;
    const DeconvolutionResult r = solve(tikhonov("gcv", *scan), n, n.delta);
    const std::string& note = r.stats.note;
    EXPECT_EQ(r.status, DeconvolutionStatus::converged) << r.stats.message;  // the status stays
    const double edge = (most ? scan->at("alpha_max") : scan->at("alpha_min")).get<double>() * norm2;
    EXPECT_NEAR(r.stats.chosen_parameter, edge, 1e-9 * edge) << scan->dump();
    EXPECT_TRUE(has(note, "gcv chose alpha = ")) << note;
    EXPECT_TRUE(has(note, "at the edge of its scan [")) << note;
    EXPECT_TRUE(has(note, most ? "(the most regularized member scanned)" : "(the least regularized member scanned)"))
        << scan->dump() << ": " << note;
    EXPECT_TRUE(has(note, "widen the scan")) << note;
    EXPECT_TRUE(has(note, "alpha_min")) << note;  // Tikhonov's hint: which parameters bound the scan
    EXPECT_EQ(r.to_json().at("stats").at("note"), note);
  }
}

TEST(ParameterChoiceEdge, TheNoteLeavesTheChoiceAsItWas) {
  // The note is words only: the chosen member and its x are those of the same scan without it.
  const Noisy n;
  const DeconvolutionResult r = solve(tikhonov("gcv", kSmall), n, n.delta);
  ASSERT_FALSE(r.stats.note.empty());
  json fixed = tikhonov("fixed");
  fixed["alpha"] = r.stats.chosen_parameter;
  const DeconvolutionResult f = solve(fixed, n, n.delta);
  EXPECT_TRUE(f.stats.note.empty());
  EXPECT_LT((f.x - r.x).norm(), 1e-10 * r.x.norm());
}

TEST(ParameterChoiceEdge, DiscrepancyMetByTheFirstMemberIsNoted) {
  // δ of 30 % of ||b||: the most regularized member of a scan from 1e-14 ||A||^2 down meets it already.
  const Noisy n;
  const DeconvolutionResult r = solve(tikhonov("discrepancy", kSmall), n, 0.3 * n.b.norm());
  EXPECT_EQ(r.status, DeconvolutionStatus::converged) << r.stats.message;
  EXPECT_TRUE(has(r.stats.note, "discrepancy chose alpha = ")) << r.stats.note;
  EXPECT_TRUE(has(r.stats.note, "the first (most regularized) member of its scan")) << r.stats.note;
  EXPECT_TRUE(has(r.stats.note, "widen the scan")) << r.stats.note;
}

TEST(ParameterChoiceEdge, TsvdGcvAtTheEndOfItsScanIsNoted) {
  // max_rank 2 cuts the scan below GCV's choice: k = 2, the least regularized member scanned.
  const Noisy n;
  const DeconvolutionResult inside = solve({{"name", "tsvd"}, {"rule", "gcv"}}, n, n.delta);
  EXPECT_TRUE(inside.stats.note.empty()) << inside.stats.note;
  const DeconvolutionResult r = solve({{"name", "tsvd"}, {"rule", "gcv"}, {"max_rank", 2}}, n, n.delta);
  EXPECT_EQ(r.stats.chosen_parameter, 2.0);
  EXPECT_TRUE(has(r.stats.note, "gcv chose k = 2 at the edge of its scan [1, 2]")) << r.stats.note;
  EXPECT_TRUE(has(r.stats.note, "max_rank")) << r.stats.note;
}

TEST(ParameterChoiceEdge, TheStabilityRowCarriesTheNote) {
  const IllPosedProblem p = make_shaw_problem(32);
  StabilityCaseInput in;
  in.noise = 0.01;
  in.scan_best = false;
  in.method = tikhonov("gcv", kSmall);
  const json edge = run_stability_case(p, in, builtin_registry());
  EXPECT_EQ(edge.at("status"), "ok");
  ASSERT_TRUE(edge.contains("note")) << edge.dump(1);
  EXPECT_TRUE(has(edge.at("note").get<std::string>(), "at the edge of its scan")) << edge.at("note");
  in.method = tikhonov("gcv");
  const json inside = run_stability_case(p, in, builtin_registry());
  EXPECT_EQ(inside.at("status"), "ok");
  EXPECT_FALSE(inside.contains("note")) << inside.at("note");
}

TEST(ParameterChoiceEdge, AReducedRowCarriesTheNotesOfItsSolves) {
  // A rule at every solve (explicit steps): reduced_model.parameter_choice counts the noted solves and keeps the
  // first note; the row's note says so. Solves without a note leave neither.
  ParameterChoiceRecord record;
  DeconvolutionStats s;
  s.rule = "gcv";
  s.parameter_name = "alpha";
  s.chosen_parameter = 1e-3;
  record.add(s);
  json row = {{"status", "ok"}, {"reduced_model", {{"parameter_choice", record.to_json()}}}};
  add_rule_notes(row);
  EXPECT_FALSE(row.at("reduced_model").at("parameter_choice").contains("notes"));
  EXPECT_FALSE(row.contains("note"));
  for (const char* note : {"first note", "second note"}) {
    s.note = note;
    record.add(s);
  }
  const json j = record.to_json();
  EXPECT_EQ(j.at("solves"), 3);
  EXPECT_EQ(j.at("notes"), json({{"solves", 2}, {"first", "first note"}}));
  row["reduced_model"]["parameter_choice"] = j;
  add_rule_notes(row);
  EXPECT_EQ(row.at("status"), "ok");
  EXPECT_EQ(row.at("note"), "the closure's parameter rule chose at the edge of its scan in 2 solve(s); the first: first note");
}
