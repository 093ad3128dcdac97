// One generic checker run over every registered deconvolver (DESIGN.md §2): registering a strategy is enough
// to have it tested here.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/closure/deconvolver.hpp"
#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/parameter_choice.hpp"
#include "core/base/registry.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {

std::vector<std::string> deconvolver_names() {
  std::vector<std::string> names;
  for (const auto& e : builtin_registry().deconvolvers.entries()) names.push_back(e.name);
  return names;
}

struct Problem {
  ForwardOperator a;
  Eigen::VectorXd x, b;
};
// η = 1.5 h on 30 nodes: κ ≈ 1e2, SPD; x a smooth bump.
Problem make_problem(Discretization d = Discretization::coarse_coarse) {
  const UniformMesh1D c = UniformMesh1D::cell_centred(0, 1, 30, false), f = UniformMesh1D::cell_centred(0, 1, 60, false);
  const GaussianKernel k(1.5 * c.spacing);
  Problem p{make_averaging_operator_1d(k, c, f, d), {}, {}};
  const UniformMesh1D& s = p.a.solution_mesh->x;
  p.x.resize(s.count);
  for (int i = 0; i < s.count; ++i) p.x(i) = std::exp(-std::pow((s.node(i) - 0.45) / 0.15, 2));
  p.b = p.a.apply(p.x);
  return p;
}

// "Clearly better than doing nothing": at most half the do-nothing error.
constexpr double kBeatFactor = 0.5;

// Combinations measured NOT to beat the do-nothing answer clearly on this problem (OMP_NUM_THREADS=1
// build/tests/closurelab_conformance_tests --gtest_filter='*DoNothing*' prints every ratio). They are real
// weaknesses of the rules, reported in issue 14's note, not tolerances: the L-curve corner is found on the
// under-regularized branch at 1 % noise (tikhonov: 43 % error), GCV of Tikhonov under-regularizes, and the
// discrepancy principle's Tikhonov answer is biased (3.2 % at 1 % noise). Each is held to its measured ratio
// (+25 %) so that it cannot get worse unnoticed; removing an entry once a rule is fixed makes the test bite.
struct KnownWeak {
  const char* method;
  const char* rule;
  double noise, measured_ratio;
};
constexpr KnownWeak kKnownWeak[] = {
    {"tikhonov", "discrepancy", 1e-2, 0.674}, {"tikhonov", "gcv", 1e-3, 0.66}, {"tikhonov", "gcv", 1e-2, 1.12},
    {"tikhonov", "lcurve", 1e-3, 0.95},       {"tikhonov", "lcurve", 1e-2, 9.03}, {"cgls", "lcurve", 1e-3, 0.869},
    {"cgls", "lcurve", 1e-2, 0.571},          {"landweber", "lcurve", 1e-3, 0.883}, {"landweber", "lcurve", 1e-2, 1.43},
    {"landweber_relaxed", "lcurve", 1e-2, 1.37}, {"cg", "lcurve", 1e-2, 1.19},    {"tsvd", "lcurve", 1e-2, 2.23}};

double allowed_ratio(const std::string& method, const std::string& rule, double noise) {
  for (const auto& k : kKnownWeak)
    if (method == k.method && rule == k.rule && noise == k.noise) return 1.25 * k.measured_ratio;
  return kBeatFactor;
}

bool supports_rule(const EntryInfo& info, const std::string& rule) {
  for (const auto& p : info.params)
    if (p.name == "rule") return std::find(p.choices.begin(), p.choices.end(), rule) != p.choices.end();
  return false;
}

class DeconvolverConformance : public ::testing::TestWithParam<std::string> {
 protected:
  const Family<Deconvolver>& family() const { return builtin_registry().deconvolvers; }
  std::unique_ptr<Deconvolver> make(json extra = json::object()) const {
    extra["name"] = GetParam();
    return family().create(extra, "/method");
  }
};

}  // namespace

TEST_P(DeconvolverConformance, SchemaIsCompleteAndDefaultsResolve) {
  const EntryInfo& info = family().info(GetParam());
  EXPECT_FALSE(info.description.empty());
  ASSERT_TRUE(supports_rule(info, "fixed")) << "every method offers a fixed parameter";
  EXPECT_TRUE(supports_rule(info, "discrepancy")) << "every method offers the discrepancy principle";
  for (const auto& p : info.params) {
    EXPECT_FALSE(p.description.empty()) << p.name;
    EXPECT_FALSE(p.default_value.is_null()) << p.name << ": every parameter has a default";
  }
  const json r = family().resolve(json{{"name", GetParam()}}, "/method");
  for (const auto& p : info.params) EXPECT_TRUE(r.contains(p.name)) << "resolved parameters echo " << p.name;
  EXPECT_THROW(make(json{{"no_such_parameter", 1}}), ConfigError);
}

TEST_P(DeconvolverConformance, FixedSolveIsFiniteConsistentAndRepeatable) {
  const Problem p = make_problem();
  auto d = make();
  EXPECT_EQ(d->name(), GetParam());
  d->setup(p.a);
  const DeconvolutionResult r = d->solve(p.b);
  ASSERT_EQ(r.x.size(), p.a.cols());
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_NE(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
  // Reported norms are the true ones (to rounding).
  EXPECT_NEAR(r.stats.residual_norm, (p.b - p.a.apply(r.x)).norm(), 1e-10 * p.b.norm());
  EXPECT_NEAR(r.stats.solution_norm, r.x.norm(), 1e-12 * r.x.norm());
  EXPECT_FALSE(r.stats.parameter_name.empty());
  EXPECT_EQ(r.stats.rule, "fixed");
  EXPECT_GE(r.cost.matvecs, 0);
  EXPECT_GE(r.cost.setup_seconds, 0.0);
  EXPECT_GE(r.cost.solve_seconds, 0.0);
  // The default parameter on exact data beats the do-nothing answer (4.5 %) clearly: measured at most 0.63 %
  // (landweber order 1; the others 1e-14 to 6e-4).
  EXPECT_LT((r.x - p.x).norm(), 0.01 * p.x.norm());
  // No hidden state: a second solve gives the same x.
  EXPECT_EQ((d->solve(p.b).x - r.x).norm(), 0.0);
  const json j = r.to_json();
  EXPECT_TRUE(j.contains("status") && j.contains("stats") && j.contains("cost"));
}

TEST_P(DeconvolverConformance, ScanReportsTrueResidualsAndStopsWhenAsked) {
  const Problem p = make_problem();
  auto d = make();
  d->setup(p.a);
  int visited = 0;
  bool saw_last = false;
  d->scan(p.b, [&](const ScanPoint& s) {
    ++visited;
    const Eigen::VectorXd x = s.solution();
    EXPECT_TRUE(x.allFinite());
    EXPECT_NEAR(s.residual_norm, (p.b - p.a.apply(x)).norm(), 1e-9 * p.b.norm()) << "parameter " << s.parameter;
    EXPECT_NEAR(s.solution_norm, x.norm(), 1e-9 * std::max(1.0, x.norm())) << "parameter " << s.parameter;
    saw_last = s.last;
    return visited < 25;
  });
  EXPECT_GE(visited, 1);
  EXPECT_TRUE(visited == 25 || saw_last) << "the scan stopped when asked or marked its last member";
}

TEST_P(DeconvolverConformance, DiscrepancyPrincipleMeetsTauDeltaOrSaysSo) {
  const Problem p = make_problem();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0, 1);
  Eigen::VectorXd e(p.b.size());
  for (auto& v : e) v = n(rng);
  e *= 1e-2 * p.b.norm() / e.norm();
  auto d = make(json{{"rule", "discrepancy"}});
  d->setup(p.a);
  const DeconvolutionResult r = d->solve(p.b + e, e.norm());
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_EQ(r.stats.rule, "discrepancy");
  if (r.status == DeconvolutionStatus::converged) EXPECT_LE(r.stats.residual_norm, 1.01 * e.norm() * (1 + 1e-12));
  else EXPECT_FALSE(r.stats.message.empty());
  // 1 % noise: the do-nothing answer's error is 4.7 %. Measured (seed 7): tsvd 0.74 %, cgls 0.80 %, relaxed
  // Landweber 1.0 %, landweber 1.9 %, cg 2.0 %, and tikhonov 4.2 % (biased: see kKnownWeak).
  std::printf("[ measured ] %s discrepancy, 1 %% noise: error %.4g\n", GetParam().c_str(), (r.x - p.x).norm() / p.x.norm());
  EXPECT_LT((r.x - p.x).norm(), 0.05 * p.x.norm());
}

TEST_P(DeconvolverConformance, RectangularOperatorIsHandledOrRefusedClearly) {
  const Problem p = make_problem(Discretization::coarse_fine);
  auto d = make();
  try {
    d->setup(p.a);
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("square"), std::string::npos) << e.what();
    return;
  }
  const DeconvolutionResult r = d->solve(p.b);
  EXPECT_EQ(r.x.size(), p.a.cols());
  EXPECT_TRUE(r.x.allFinite());
  if (r.status == DeconvolutionStatus::numerical_issue) {
    EXPECT_FALSE(r.stats.message.empty());
  }
}

TEST_P(DeconvolverConformance, BadDataIsAConfigError) {
  const Problem p = make_problem();
  auto d = make();
  d->setup(p.a);
  Eigen::VectorXd b = p.b;
  b(0) = INFINITY;
  EXPECT_THROW(d->solve(b), ConfigError);
  EXPECT_THROW(d->solve(p.b.head(5)), ConfigError);
}

// The do-nothing answer x = b (the data taken as the solution: the zero-order closure) has a 4.5 % error on
// this problem. Every rule a method offers must beat it clearly, however its status reads: the fixed default
// on exact data, and every parameter-choice rule on data with 0.1 % and 1 % noise (δ given).
TEST_P(DeconvolverConformance, EveryRuleBeatsTheDoNothingAnswerClearly) {
  const Problem p = make_problem();
  const EntryInfo& info = family().info(GetParam());
  int rules = 0;
  for (const char* rule : {"fixed", "discrepancy", "gcv", "lcurve"}) {
    if (!supports_rule(info, rule)) continue;
    ++rules;
    const bool fixed = std::string(rule) == "fixed";
    for (double noise : fixed ? std::vector<double>{0.0} : std::vector<double>{1e-3, 1e-2}) {
      SCOPED_TRACE(std::string(rule) + ", noise " + std::to_string(noise));
      std::mt19937_64 rng(11);
      std::normal_distribution<double> n(0, 1);
      Eigen::VectorXd e(p.b.size());
      for (auto& v : e) v = n(rng);
      e *= noise * p.b.norm() / e.norm();
      const double do_nothing = (p.b + e - p.x).norm() / p.x.norm();
      ASSERT_GT(do_nothing, 0.04);
      auto d = make(json{{"rule", rule}});
      try {
        d->setup(p.a);
      } catch (const ConfigError& err) {  // a rule this configuration cannot use must say why, naming the key
        EXPECT_NE(std::string(err.what()).find("/"), std::string::npos) << err.what();
        continue;
      }
      const DeconvolutionResult r = d->solve(p.b + e, e.norm());
      ASSERT_EQ(r.x.size(), p.a.cols());
      EXPECT_NE(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
      const double err = (r.x - p.x).norm() / p.x.norm();
      std::printf("[ measured ] %s %s noise %g: error %.4g, do-nothing %.4g, ratio %.3g\n", GetParam().c_str(), rule,
                  noise, err, do_nothing, err / do_nothing);
      EXPECT_LT(err, allowed_ratio(GetParam(), rule, noise) * do_nothing) << "error " << err << " vs do-nothing " << do_nothing;
    }
  }
  EXPECT_GE(rules, 2) << "every method offers fixed and at least one rule";
}

INSTANTIATE_TEST_SUITE_P(AllRegistered, DeconvolverConformance, ::testing::ValuesIn(deconvolver_names()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });
