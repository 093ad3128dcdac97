// Many right-hand sides at once (Deconvolver::solve_columns) and Tikhonov's dual backend x = Aᵀ(AAᵀ + αI)⁻¹b.
// Asserted: the columns' solutions equal one solve per column to round-off (and their statistics and statuses), for
// the strategies that batch (Tikhonov spectral and dual) and for the default (Landweber), also on a badly scaled
// column, which falls back to one solve per column; the dual backend equals the spectral one within its condition
// number times the unit roundoff on a wide coarse–fine Gaussian operator (the 2D force-density model's shape); it
// equals the stacked QR with a first-difference regularizer (with and without a null space); it refuses what it
// cannot serve (a rule, the paper form, a second difference) at /backend, and an α that makes
// its m × m system singular to ~1e-5 is a numerical issue, never `converged`.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "experiments/testproblems/ill_posed_problems.hpp"

using namespace closurelab;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A wide operator: coarse data (16 nodes) of a fine reconstruction (4 × finer), the shape of the 2D model's maps.
ForwardOperator wide_gaussian() {
  GaussianProblemSpec spec;
  spec.coarse_count = 16;
  spec.fine_ratio = 4;
  spec.discretization = Discretization::coarse_fine;
  return make_gaussian_problem(spec).a;
}

std::unique_ptr<Deconvolver> bound(const json& method, const ForwardOperator& a) {
  auto d = builtin_registry().deconvolvers.create(method, "/method");
  d->setup(a);
  return d;
}

// Columns: unit data, a smooth profile and one column scaled by 2^-60 (the badly scaled path).
Eigen::MatrixXd data_columns(Eigen::Index m) {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(m, 5);
  for (int k = 0; k < 3; ++k) b(k * (m / 3), k) = 1.0;
  for (Eigen::Index i = 0; i < m; ++i) b(i, 3) = std::sin(3.0 * static_cast<double>(i) / static_cast<double>(m));
  b.col(4) = std::ldexp(1.0, -60) * b.col(3);
  return b;
}

void expect_columns_match_solves(const json& method, const ForwardOperator& a) {
  SCOPED_TRACE(method.dump());
  const auto d = bound(method, a);
  const Eigen::MatrixXd b = data_columns(a.rows());
  std::vector<DeconvolutionResult> results;
  const Eigen::MatrixXd x = d->solve_columns(b, 0.0, &results);
  ASSERT_EQ(x.cols(), b.cols());
  ASSERT_EQ(results.size(), static_cast<std::size_t>(b.cols()));
  for (Eigen::Index k = 0; k < b.cols(); ++k) {
    const DeconvolutionResult one = d->solve(b.col(k));
    // Matrix products sum in another order than matrix-vector ones: agreement to a few ulps of the solution's
    // scale times the inner dimension.
    const double tol = 64 * kEps * static_cast<double>(a.cols()) * std::max(one.x.cwiseAbs().maxCoeff(), 1e-300);
    EXPECT_LE((x.col(k) - one.x).cwiseAbs().maxCoeff(), tol) << "column " << k;
    EXPECT_EQ(results[static_cast<std::size_t>(k)].status, one.status) << "column " << k;
    EXPECT_EQ(results[static_cast<std::size_t>(k)].cost.matvecs, one.cost.matvecs) << "column " << k;
    EXPECT_NEAR(results[static_cast<std::size_t>(k)].stats.residual_norm, one.stats.residual_norm,
                1e-9 * std::max(one.stats.residual_norm, b.col(k).norm()));
    EXPECT_NEAR(results[static_cast<std::size_t>(k)].stats.solution_norm, one.stats.solution_norm,
                1e-9 * one.stats.solution_norm);
    EXPECT_EQ(results[static_cast<std::size_t>(k)].stats.chosen_parameter, one.stats.chosen_parameter);
  }
}

}  // namespace

TEST(DeconvolverSolveColumns, EqualsOneSolvePerColumn) {
  const ForwardOperator a = wide_gaussian();
  expect_columns_match_solves({{"name", "tikhonov"}, {"alpha", 1e-6}, {"backend", "spectral"}}, a);
  expect_columns_match_solves({{"name", "tikhonov"}, {"alpha", 1e-6}, {"backend", "dual"}}, a);
  expect_columns_match_solves({{"name", "landweber_relaxed"}, {"iterations", 5}}, a);  // the default, column by column
  // A rule: one choice per column, as solve() makes it.
  expect_columns_match_solves({{"name", "tikhonov"}, {"rule", "gcv"}}, a);
}

TEST(DeconvolverSolveColumns, KeepsTheStatusOfASwampedAlpha) {
  const ForwardOperator a = wide_gaussian();
  const auto d = bound({{"name", "tikhonov"}, {"alpha", 1e300}, {"backend", "spectral"}}, a);
  std::vector<DeconvolutionResult> results;
  d->solve_columns(data_columns(a.rows()).leftCols(2), 0.0, &results);
  ASSERT_EQ(results.size(), 2u);
  for (const auto& r : results) EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue) << r.stats.message;
}

TEST(TikhonovDual, EqualsTheSpectralBackendWithinItsCondition) {
  const ForwardOperator a = wide_gaussian();
  ASSERT_LT(a.rows(), a.cols());
  const Eigen::VectorXd b = data_columns(a.rows()).col(3);
  for (const double rel : {1e-2, 1e-6, 1e-9}) {
    const double alpha = rel * a.norm2_estimate() * a.norm2_estimate();
    const DeconvolutionResult spectral = bound({{"name", "tikhonov"}, {"alpha", alpha}, {"backend", "spectral"}}, a)->solve(b);
    const DeconvolutionResult dual = bound({{"name", "tikhonov"}, {"alpha", alpha}, {"backend", "dual"}}, a)->solve(b);
    ASSERT_EQ(dual.status, DeconvolutionStatus::converged) << dual.stats.message;
    // The dual system's condition is about 1 + 1/rel: its relative error bound, with a factor for the sizes.
    EXPECT_LE((dual.x - spectral.x).norm(), 100 * kEps * (1.0 + 1.0 / rel) * spectral.x.norm()) << "alpha/||A||^2 = " << rel;
  }
}

namespace {

// A wide random operator (6 data, 12 unknowns) whose links (ForwardOperator::difference_links) are two chains:
// unknowns 0–5 with a link from 0 to a known zero (anchored: L has no null space there), 6–11 with none (free: its
// constant lies in null(L)), weighted unevenly.
ForwardOperator two_chains() {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(6, 12);
  for (Eigen::Index i = 0; i < 6; ++i)
    for (Eigen::Index j = 0; j < 12; ++j) m(i, j) = std::exp(-0.1 * static_cast<double>((2 * i - j) * (2 * i - j))) + 0.01 * std::sin(static_cast<double>(i + 3 * j));
  ForwardOperator a = ForwardOperator::from_dense(m);
  std::vector<Eigen::Triplet<double>> t{{0, 0, 1.5}};
  int row = 1;
  for (int j = 0; j + 1 < 12; ++j) {
    if (j == 5) continue;
    const double w = 1.0 + 0.3 * j;
    t.emplace_back(row, j, -w);
    t.emplace_back(row, j + 1, w);
    ++row;
  }
  Eigen::SparseMatrix<double> l(row, 12);
  l.setFromTriplets(t.begin(), t.end());
  a.difference_links = l;
  return a;
}

}  // namespace

// The dual backend with a first difference L (x = G Aᵀ y + N z, the bordered dual system) against the stacked QR of
// [A; √α L] (backend dense), the least-squares problem solved without the dual's squared condition: a 1D first
// difference (null space: the constants), the zero-end difference (none) and links with one free and one anchored
// component. Both solve the same normal equations; the dual system squares the condition as the C = I dual does, so
// the bound is the same as there: 100 ε (1 + ‖A‖²/α) relative (measured: 2e-15 to 1.6e-13 at α/‖A‖² = 1e-2, 1e-12 to
// 8.4e-9 at 1e-6, against bounds of 2.2e-12 and 2.2e-8).
TEST(TikhonovDual, WithAFirstDifferenceEqualsTheStackedQr) {
  const ForwardOperator gaussian = wide_gaussian(), chains = two_chains();
  for (const auto& [a, regularizer] : {std::pair{&gaussian, "first_difference"}, std::pair{&gaussian, "first_difference_zero_ends"},
                                        std::pair{&chains, "first_difference_zero_ends"}}) {
    const Eigen::VectorXd b = data_columns(a->rows()).col(3) + 0.2 * data_columns(a->rows()).col(0);
    for (const double rel : {1e-2, 1e-6}) {
      const double alpha = rel * a->norm2_estimate() * a->norm2_estimate();
      SCOPED_TRACE(std::string(regularizer) + " alpha/||A||^2 = " + std::to_string(rel));
      const json method = {{"name", "tikhonov"}, {"alpha", alpha}, {"regularizer", regularizer}};
      json dense = method, dual = method;
      dense["backend"] = "dense";
      dual["backend"] = "dual";
      const DeconvolutionResult ref = bound(dense, *a)->solve(b), r = bound(dual, *a)->solve(b);
      ASSERT_EQ(r.status, DeconvolutionStatus::converged) << r.stats.message;
      EXPECT_LE((r.x - ref.x).norm(), 100 * kEps * (1.0 + 1.0 / rel) * ref.x.norm());
    }
  }
  expect_columns_match_solves({{"name", "tikhonov"}, {"alpha", 1e-6}, {"backend", "dual"}, {"regularizer", "first_difference_zero_ends"}},
                              chains);
}

TEST(TikhonovDual, RefusesWhatItCannotServe) {
  const ForwardOperator a = wide_gaussian();
  const auto path_of = [&](const json& method) {
    try {
      bound(method, a);
    } catch (const ConfigError& e) {
      return e.path();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(path_of({{"name", "tikhonov"}, {"backend", "dual"}, {"rule", "gcv"}}), "/backend");
  EXPECT_EQ(path_of({{"name", "tikhonov"}, {"backend", "dual"}, {"regularizer", "second_difference"}}), "/backend");
  const ForwardOperator square = ForwardOperator::from_dense(Eigen::MatrixXd::Identity(4, 4));
  try {
    bound({{"name", "tikhonov"}, {"backend", "dual"}, {"form", "paper"}}, square);
    ADD_FAILURE() << "the paper form was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/backend");
  }
}

TEST(TikhonovDual, ANearlySingularSystemIsANumericalIssue) {
  // Two nearly parallel rows: AAᵀ = [[1, 1], [1, 1 + 1e-14]] has condition ~4e14, far beyond what a tiny α lifts.
  Eigen::MatrixXd m(2, 3);
  m << 1.0, 0.0, 0.0, 1.0, 1e-7, 0.0;
  const ForwardOperator a = ForwardOperator::from_dense(m);
  const DeconvolutionResult r =
      bound({{"name", "tikhonov"}, {"alpha", 1e-20}, {"backend", "dual"}}, a)->solve(Eigen::Vector2d(1.0, 0.5));
  EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue);
  EXPECT_NE(r.stats.message.find("reciprocal condition"), std::string::npos) << r.stats.message;
  // The spectral backend solves the same problem without squaring the condition.
  EXPECT_EQ(bound({{"name", "tikhonov"}, {"alpha", 1e-20}, {"backend", "spectral"}}, a)->solve(Eigen::Vector2d(1.0, 0.5)).status,
            DeconvolutionStatus::converged);
}
