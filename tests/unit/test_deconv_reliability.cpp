// No deconvolution result is `converged` when it fits the data no better than the
// trivial answer x = 0, divides by singular values below the numerical rank, solves with a factorization that is
// singular to working precision, or reports a non-finite norm for finite data.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"

using namespace closurelab;

namespace {

DeconvolutionResult solve(const json& method, const ForwardOperator& a, const Eigen::VectorXd& b) {
  auto d = builtin_registry().deconvolvers.create(method, "/method");
  d->setup(a);
  return d->solve(b, 0.0);
}

bool mentions(const DeconvolutionResult& r, const std::string& what) {
  return r.stats.message.find(what) != std::string::npos;
}

}  // namespace

// Item 4: A = 0, order 1000 gave x = 1001 b with residual ||b||, `converged`.
TEST(DeconvReliability, LandweberOnTheZeroOperatorIsNotConverged) {
  const ForwardOperator a = ForwardOperator::from_dense(Eigen::MatrixXd::Zero(3, 3));
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, -2.0, 0.5);
  const DeconvolutionResult r = solve({{"name", "landweber"}, {"order", 1000}}, a, b);
  EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
  EXPECT_TRUE(mentions(r, "no better than x = 0")) << r.stats.message;
  EXPECT_TRUE(mentions(r, "spectrum in (0, 2)")) << r.stats.message;
}

// Item 4: A = [[1,1],[1,1]] (eigenvalues 0 and 2), b = (1, 0): (I - A) is orthogonal, so the residual stays at
// ||b|| while x grows to (501, -500).
TEST(DeconvReliability, LandweberOnASingularOperatorIsNotConverged) {
  Eigen::MatrixXd m(2, 2);
  m << 1, 1, 1, 1;
  const ForwardOperator a = ForwardOperator::from_dense(m);
  const Eigen::VectorXd b = Eigen::Vector2d(1.0, 0.0);
  const DeconvolutionResult r = solve({{"name", "landweber"}, {"order", 1000}}, a, b);
  EXPECT_GT(r.x.norm(), 100.0);  // the series' own answer, kept for inspection
  EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
}

// Item 4: rule lcurve on A = 0 picked some order and called it converged.
TEST(DeconvReliability, LandweberLcurveOnTheZeroOperatorIsNotConverged) {
  const ForwardOperator a = ForwardOperator::from_dense(Eigen::MatrixXd::Zero(4, 4));
  const Eigen::VectorXd b = Eigen::Vector4d(1, 2, 3, 4);
  const DeconvolutionResult r = solve({{"name", "landweber"}, {"rule", "lcurve"}}, a, b);
  if (r.x.isZero(0)) GTEST_SKIP() << "the rule chose x = 0";
  EXPECT_NE(r.status, DeconvolutionStatus::converged) << r.stats.message;
}

// A well-posed Landweber solve is untouched by the guard: A = 0.5 I, order 60 reaches x = 2 b to 2^-61.
TEST(DeconvReliability, LandweberOnAWellPosedOperatorStaysConverged) {
  const ForwardOperator a = ForwardOperator::from_dense(0.5 * Eigen::MatrixXd::Identity(3, 3));
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, -2.0, 0.5);
  const DeconvolutionResult r = solve({{"name", "landweber"}, {"order", 60}}, a, b);
  EXPECT_EQ(r.status, DeconvolutionStatus::converged) << r.stats.message;
  EXPECT_LT((r.x - 2 * b).norm(), 1e-12);
}

// Item 4: omega = 1.9999999 on the identity: the error factor per step is -0.9999999, so after the default 50
// iterations x ~ 0 (or ~ 2b) and the residual is 0.999995 ||b||.
TEST(DeconvReliability, LandweberRelaxedNearTwoOverNormSquaredIsNotConverged) {
  const ForwardOperator a = ForwardOperator::from_dense(Eigen::MatrixXd::Identity(3, 3));
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, 2.0, 3.0);
  const DeconvolutionResult r = solve({{"name", "landweber_relaxed"}, {"omega", 1.9999999}}, a, b);
  EXPECT_NE(r.status, DeconvolutionStatus::converged) << r.stats.message;
  EXPECT_TRUE(mentions(r, "oscillates")) << r.stats.message;
  // A moderate over-relaxation converges and is kept: |1 - 1.5|^50 = 9e-16.
  const DeconvolutionResult ok = solve({{"name", "landweber_relaxed"}, {"omega", 1.5}}, a, b);
  EXPECT_EQ(ok.status, DeconvolutionStatus::converged) << ok.stats.message;
  EXPECT_LT((ok.x - b).norm(), 1e-12 * b.norm());
}

// Item 5: a rank-3 5x5 matrix with k = 5 kept singular values ~1e-16 and returned ||x|| = 5e15.
TEST(DeconvReliability, TsvdAboveTheNumericalRankIsNotConverged) {
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(5, 3);
  u << 1, 2, 0, 0, 1, 1, 3, 0, 1, 1, 1, 1, 0, 2, 5;
  const Eigen::MatrixXd m = u * u.transpose();  // rank 3, symmetric
  const ForwardOperator a = ForwardOperator::from_dense(m);
  Eigen::VectorXd b(5);
  b << 0.3, -0.7, 0.2, 1.0, 0.5;  // not in the range
  const DeconvolutionResult r = solve({{"name", "tsvd"}, {"k", 5}}, a, b);
  EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
  EXPECT_TRUE(mentions(r, "numerical rank 3")) << r.stats.message;
  const DeconvolutionResult k3 = solve({{"name", "tsvd"}, {"k", 3}}, a, b);
  EXPECT_EQ(k3.status, DeconvolutionStatus::converged) << k3.stats.message;
  EXPECT_LT(k3.stats.residual_norm, b.norm());
  // The threshold form keeping every singular value is the same thing.
  const DeconvolutionResult t = solve({{"name", "tsvd"}, {"truncation", "threshold"}, {"threshold", 1e-300}}, a, b);
  EXPECT_EQ(t.status, DeconvolutionStatus::numerical_issue) << t.stats.message;
}

// Item 5: Tikhonov on a 12x12 Hilbert matrix with alpha = 1e-300: dense said numerical_issue, sparse (CHOLMOD)
// said converged with a relative error of 10.2.
TEST(DeconvReliability, TikhonovWithASingularFactorizationIsNotConverged) {
  const int n = 12;
  Eigen::MatrixXd h(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) h(i, j) = 1.0 / (i + j + 1);
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(n);
  const Eigen::VectorXd b = h * x;
  for (const std::string backend : {"dense", "sparse"}) {
    SCOPED_TRACE(backend);
    const ForwardOperator a =
        backend == "sparse" ? ForwardOperator::from_sparse(h.sparseView()) : ForwardOperator::from_dense(h);
    const DeconvolutionResult r = solve({{"name", "tikhonov"}, {"alpha", 1e-300}, {"backend", backend}}, a, b);
    EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
    // A well-conditioned alpha on the same system is a result (cond(H'H + 1e-8 I) ~ 1e8).
    const DeconvolutionResult ok = solve({{"name", "tikhonov"}, {"alpha", 1e-8}, {"backend", backend}}, a, b);
    EXPECT_EQ(ok.status, DeconvolutionStatus::converged) << ok.stats.message;
    EXPECT_LT((ok.x - x).norm() / x.norm(), 0.1);
  }
}

// Item 1: x = (1, 1e150, 1e300) is representable but its squared norm is not: the norm is computed scaled.
TEST(DeconvReliability, SolutionNormOfAHugeButFiniteSolutionIsFinite) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Identity(3, 3);
  const ForwardOperator a = ForwardOperator::from_dense(m);
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, 1e150, 1e300);
  for (const json& method : {json{{"name", "tsvd"}, {"k", 3}}, json{{"name", "cgls"}}, json{{"name", "tikhonov"}}}) {
    SCOPED_TRACE(method.dump());
    const DeconvolutionResult r = solve(method, a, b);
    ASSERT_TRUE(r.x.allFinite());
    EXPECT_TRUE(std::isfinite(r.stats.solution_norm)) << r.stats.solution_norm;
    EXPECT_NEAR(r.stats.solution_norm / 1e300, 1.0, 1e-6);
    EXPECT_TRUE(std::isfinite(r.stats.residual_norm));
  }
}

// The reported case: diag(1, 1e-150, 1e-300), b = (1, 1, 1), tsvd k = 3 gave the right x with
// `solution_norm: null` (||x||^2 = 1e600 overflows) while `converged`. The norm is now finite; k = 3 is above
// the numerical rank (1: the others are below 3 eps sigma_1), so the result is a numerical_issue.
TEST(DeconvReliability, TsvdOnAWidelyScaledDiagonalHasAFiniteNormAndAnHonestStatus) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3, 3);
  m.diagonal() << 1.0, 1e-150, 1e-300;
  const ForwardOperator a = ForwardOperator::from_dense(m);
  const DeconvolutionResult r = solve({{"name", "tsvd"}, {"k", 3}}, a, Eigen::VectorXd::Ones(3));
  ASSERT_TRUE(r.x.allFinite());
  EXPECT_TRUE(std::isfinite(r.stats.solution_norm));
  EXPECT_NEAR(r.stats.solution_norm / 1e300, 1.0, 1e-6);
  EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
}

// Smaller item: a rescaled operator (max entry beyond 2^±32) kept its meshes but lost ForwardOperator::link_weights,
// so a viscosity-weighted Tikhonov prior silently fell back to unit weights on badly scaled data. Scaling A by
// 2^40 and alpha by 2^80 must give x / 2^40, with the weights.
TEST(DeconvReliability, ARescaledOperatorKeepsItsLinkWeights) {
  const int rows = 6, cols = 8;
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) m(i, j) = std::exp(-0.5 * std::pow((i + 0.5) * cols / rows - (j + 0.5), 2));
  Eigen::VectorXd w(cols + 1);
  for (int i = 0; i <= cols; ++i) w[i] = i < cols / 2 ? 1.0 : 0.01;  // a two-viscosity channel
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(rows, 0.5, 1.5);
  const double alpha = 1e-2;
  auto solve_with = [&](double scale, bool weighted) {
    ForwardOperator a = ForwardOperator::from_dense(scale * m);
    if (weighted) a.link_weights = w;
    return solve({{"name", "tikhonov"}, {"regularizer", "first_difference_zero_ends"}, {"alpha", alpha * scale * scale},
                  {"backend", "dense"}},
                 a, b);
  };
  const DeconvolutionResult plain = solve_with(1.0, true), unweighted = solve_with(1.0, false);
  const DeconvolutionResult scaled = solve_with(std::ldexp(1.0, 40), true);
  ASSERT_EQ(plain.status, DeconvolutionStatus::converged) << plain.stats.message;
  ASSERT_EQ(scaled.status, DeconvolutionStatus::converged) << scaled.stats.message;
  EXPECT_GT((unweighted.x - plain.x).norm(), 1e-2 * plain.x.norm());  // the weights matter here
  EXPECT_LT((std::ldexp(1.0, 40) * scaled.x - plain.x).norm(), 1e-10 * plain.x.norm());
}

// Item 1: GCV on data of 1e200 had every GCV value overflow when unscaled (r^2 ~ 1e400), so the rule found none
// ("cannot evaluate the GCV function"). The minimizer is scale-free: the same alpha as for the data / 1e200.
TEST(DeconvReliability, GcvOnHugeDataPicksTheSameParameter) {
  const int n = 16;
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = std::exp(-0.3 * (i - j) * (i - j));
  const ForwardOperator a = ForwardOperator::from_dense(m);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.4 * i) + 1e-3 * std::cos(7.0 * i);
  for (const std::string method : {"tikhonov", "tsvd"}) {
    SCOPED_TRACE(method);
    const json cfg = {{"name", method}, {"rule", "gcv"}};
    const DeconvolutionResult plain = solve(cfg, a, b);
    const DeconvolutionResult huge = solve(cfg, a, 1e200 * b);
    ASSERT_EQ(plain.status, DeconvolutionStatus::converged) << plain.stats.message;
    ASSERT_EQ(huge.status, DeconvolutionStatus::converged) << huge.stats.message;
    EXPECT_EQ(huge.stats.chosen_parameter, plain.stats.chosen_parameter);
    EXPECT_LT((huge.x / 1e200 - plain.x).norm(), 1e-12 * plain.x.norm());
  }
}
