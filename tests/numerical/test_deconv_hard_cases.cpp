// The hard-case stability suite as gtests, through the same run_stability_case the
// "deconvolution_stability" experiment uses (experiments/stability/*.json; table in results/stability/).
// Problems: Gaussian averaging coarse–coarse with κ from ~1e2 to ~1e14, fine–fine (κ beyond 1e16), the
// truncated sampled Gaussian with negative eigenvalues, and shaw / deriv2 / phillips with data made without the
// inverse crime; noise 0, 1e-4, 1e-2, 1e-1 (seed 20261125, as in the committed table).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>

#include "core/closure/deconvolver.hpp"
#include "core/base/registry.hpp"
#include "experiments/testproblems/ill_posed_problems.hpp"
#include "experiments/testproblems/stability_case.hpp"

using namespace closurelab;

namespace {

constexpr std::uint64_t seed = 20261125;

std::vector<std::pair<std::string, IllPosedProblem>> square_problems() {
  std::vector<std::pair<std::string, IllPosedProblem>> v;
  for (double eh : {1.5, 2.0, 3.0, 4.0}) {
    GaussianProblemSpec s;
    s.coarse_count = 32;
    s.eta_over_h = eh;
    v.emplace_back("coarse_coarse eta/h=" + std::to_string(eh), make_gaussian_problem(s));
  }
  for (int r : {2, 4}) {
    GaussianProblemSpec s;
    s.coarse_count = 32;
    s.fine_ratio = r;
    s.discretization = Discretization::fine_fine;
    v.emplace_back("fine_fine r=" + std::to_string(r), make_gaussian_problem(s));
  }
  for (double c : {1.5, 2.0}) {
    GaussianProblemSpec s;
    s.coarse_count = 32;
    s.eta_over_h = 3.0;
    s.kernel = "cutoff_gaussian";
    s.cutoff_in_eta = c;
    v.emplace_back("cutoff " + std::to_string(c), make_gaussian_problem(s));
  }
  v.emplace_back("shaw", make_shaw_problem(64));
  v.emplace_back("deriv2", make_deriv2_problem(64));
  v.emplace_back("phillips", make_phillips_problem(64));
  return v;
}

json run_case(const IllPosedProblem& p, const std::string& method, double noise) {
  StabilityCaseInput in;
  in.noise = noise;
  in.seed = seed;
  in.method = {{"name", method}, {"rule", "discrepancy"}};
  return run_stability_case(p, in, builtin_registry());
}

}  // namespace

TEST(DeconvHardCases, ConditionNumbersSpanTheRange) {
  GaussianProblemSpec s;
  s.coarse_count = 32;
  s.eta_over_h = 1.5;
  const double well = condition_number(make_gaussian_problem(s).a);
  EXPECT_GT(well, 30.0);
  EXPECT_LT(well, 1e3);
  s.eta_over_h = 4.0;
  EXPECT_GT(condition_number(make_gaussian_problem(s).a), 1e13);
  s.eta_over_h = 2.0;
  s.discretization = Discretization::fine_fine;
  EXPECT_GT(condition_number(make_gaussian_problem(s).a), 1e16);  // σ_min at rounding level
}

TEST(DeconvHardCases, NoNonFiniteOutputAndTheDiscrepancyPrincipleIsNearTheBestParameter) {
  // Bound on rule error / best scanned error for the noisy cases. Factor 2 for tikhonov, cgls and both
  // Landwebers. Measured exceptions, kept visible rather than hidden: tsvd's integer truncation index lands one
  // step early (worst 2.06, fine–fine r=2 at 1e-4), and cg's residual is not monotone, so the rule stops at its
  // first clear minimum (worst 2.09, coarse–coarse η/h=3 at 1e-1); both are bounded by 2.5 here.
  const std::map<std::string, double> bound = {{"tikhonov", 2.0}, {"cgls", 2.0}, {"landweber_relaxed", 2.0},
                                               {"landweber", 2.0}, {"tsvd", 2.5},  {"cg", 2.5}};
  int checked = 0;
  for (const auto& [label, p] : square_problems()) {
    for (const auto& [method, limit] : bound) {
      for (double noise : {0.0, 1e-4, 1e-2, 1e-1}) {
        const json row = run_case(p, method, noise);
        const std::string where = label + " " + method + " noise " + std::to_string(noise);
        EXPECT_TRUE(row["all_finite"].get<bool>()) << where;
        if (noise == 0.0 || row["status"] == "numerical_issue") continue;  // refusals are checked below
        const double ratio = row["errors"]["ratio_to_best"].get<double>();
        EXPECT_LE(ratio, limit) << where;
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 150);
}

TEST(DeconvHardCases, TruncatedSampledGaussianHasNegativeEigenvaluesThatAreDetected) {
  // σ = η/√2 = 2.1 h; truncation at 2η = 2.8σ (DESIGN.md §6).
  GaussianProblemSpec s;
  s.coarse_count = 32;
  s.eta_over_h = 3.0;
  s.kernel = "cutoff_gaussian";
  s.cutoff_in_eta = 2.0;
  const IllPosedProblem p = make_gaussian_problem(s);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(p.a.to_dense(), Eigen::EigenvaluesOnly);
  ASSERT_LT(eig.eigenvalues().minCoeff(), -1e-4);

  // Plain CG refuses the operator with a clear status.
  auto cg = builtin_registry().deconvolvers.create(json{{"name", "cg"}}, "/m");
  cg->setup(p.a);
  const DeconvolutionResult rc = cg->solve(p.b_exact);
  EXPECT_EQ(rc.status, DeconvolutionStatus::numerical_issue);
  EXPECT_NE(rc.stats.message.find("not positive definite"), std::string::npos) << rc.stats.message;
  // Without the spectral check, the curvature test still refuses or CG stays bounded.
  auto cg2 = builtin_registry().deconvolvers.create(json{{"name", "cg"}, {"spd_check", false}, {"iterations", 500}}, "/m");
  cg2->setup(p.a);
  const DeconvolutionResult rc2 = cg2->solve(p.b_exact);
  EXPECT_TRUE(rc2.x.allFinite());
  EXPECT_TRUE(rc2.status == DeconvolutionStatus::numerical_issue || (rc2.x - p.x_true).norm() < p.x_true.norm())
      << rc2.stats.message;

  // The Landweber series (4.3) has a growing mode: a long series detects it and stops with bounded x.
  auto lw = builtin_registry().deconvolvers.create(json{{"name", "landweber"}, {"order", 100000}}, "/m");
  lw->setup(p.a);
  const DeconvolutionResult rl = lw->solve(p.b_exact);
  EXPECT_EQ(rl.status, DeconvolutionStatus::numerical_issue);
  EXPECT_NE(rl.stats.message.find("growing mode"), std::string::npos) << rl.stats.message;
  EXPECT_TRUE(rl.x.allFinite());
  EXPECT_LT((rl.x - p.x_true).norm(), 0.2 * p.x_true.norm());
  EXPECT_LT(rl.stats.iterations, 100000);

  // The paper's low orders are unaffected (the growing mode is ~1e-3 per order).
  auto lw2 = builtin_registry().deconvolvers.create(json{{"name", "landweber"}, {"order", 2}}, "/m");
  lw2->setup(p.a);
  EXPECT_EQ(lw2->solve(p.b_exact).status, DeconvolutionStatus::converged);

  // Tikhonov's paper form (A + αI)x = b is refused for α below |λ_min|, the least-squares form is fine.
  auto tp = builtin_registry().deconvolvers.create(json{{"name", "tikhonov"}, {"form", "paper"}, {"alpha", 1e-5}}, "/m");
  tp->setup(p.a);
  EXPECT_EQ(tp->solve(p.b_exact).status, DeconvolutionStatus::numerical_issue);
  auto tl = builtin_registry().deconvolvers.create(json{{"name", "tikhonov"}, {"alpha", 1e-5}}, "/m");
  tl->setup(p.a);
  EXPECT_EQ(tl->solve(p.b_exact).status, DeconvolutionStatus::converged);
}

TEST(DeconvHardCases, LandweberSeriesOnNonAveragingOperatorsIsFlagged) {
  // deriv2 is negative definite and phillips has ‖A‖ ≈ 6: the series (4.3) diverges; it must say so.
  for (const IllPosedProblem& p : {make_deriv2_problem(64), make_phillips_problem(64)}) {
    auto lw = builtin_registry().deconvolvers.create(json{{"name", "landweber"}, {"order", 10}}, "/m");
    lw->setup(p.a);
    const DeconvolutionResult r = lw->solve(p.b_exact);
    EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue) << p.name;
    EXPECT_TRUE(r.x.allFinite()) << p.name;
  }
}

TEST(DeconvHardCases, GcvAndLcurveRulesGiveFiniteSolutions) {
  // GCV and the L-curve corner need no noise level; they are known to fail on some realizations (GCV's
  // flat minimum near full rank, the L-curve for smooth solutions, Hanke 1996). Only finiteness and a
  // clean status are asserted; their error ratios are recorded in results/stability (rules table).
  for (const IllPosedProblem& p : {make_shaw_problem(64), make_phillips_problem(64), make_deriv2_problem(64)}) {
    for (const std::string method : {"tikhonov", "tsvd"}) {
      for (const std::string rule : {"gcv", "lcurve"}) {
        StabilityCaseInput in;
        in.noise = 1e-2;
        in.seed = seed;
        in.method = {{"name", method}, {"rule", rule}};
        const json row = run_stability_case(p, in, builtin_registry());
        EXPECT_TRUE(row["all_finite"].get<bool>()) << p.name << " " << method << " " << rule;
        EXPECT_EQ(row["deconvolution_status"], "converged") << p.name << " " << method << " " << rule;
      }
    }
  }
}
