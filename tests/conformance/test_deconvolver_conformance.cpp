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
  // The default parameter regularizes sensibly on this κ ≈ 1e2 problem: the error is below 30 %.
  EXPECT_LT((r.x - p.x).norm(), 0.3 * p.x.norm());
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
  EXPECT_LT((r.x - p.x).norm(), 0.5 * p.x.norm());
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

INSTANTIATE_TEST_SUITE_P(AllRegistered, DeconvolverConformance, ::testing::ValuesIn(deconvolver_names()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });
