#pragma once
// The factorisations behind Tikhonov's backends (tikhonov.cpp): CHOLMOD with its condition estimate (the paper
// form, sparse), the stacked QR of [A; √α L] (the least-squares form, dense and sparse) and the dual systems
// AAᵀ + αI by Cholesky and, for a first-difference L, A G Aᵀ + αI bordered by the null space (backend dual).
#include <Eigen/CholmodSupport>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SparseQR>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/base/errors.hpp"

namespace closurelab::tikhonov_detail {

using SpMat = Eigen::SparseMatrix<double>;

// CHOLMOD's factorization with its reciprocal condition estimate (min/max of diag(L), squared for LL'):
// CHOLMOD only fails on a non-positive pivot, so a matrix that is singular to working precision (A'A + 1e-300 I
// for a 12x12 Hilbert A) factorizes "successfully" into garbage; the estimate says so.
class Cholmod : public Eigen::CholmodDecomposition<SpMat> {
 public:
  double rcond() { return m_cholmodFactor ? cholmod_rcond(m_cholmodFactor, &cholmod()) : 0.0; }
};

// A factorization whose reciprocal condition number is below the unit roundoff solves with no correct digit.
constexpr double singular_rcond = std::numeric_limits<double>::epsilon();

// The least-squares form at one α as the stacked problem [A; √α L] x ≈ [b; 0] by QR: the stacked matrix is
// A P = Q R (P the column permutation: pivoting in the dense QR, COLAMD in the sparse one), so RᵀR = AᵀA + α LᵀL
// without forming it and R's condition number is the stacked matrix's, not its square.
class StackedQr {
 public:
  StackedQr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& l, double alpha) : m_(a.rows()), n_(a.cols()) {
    Eigen::MatrixXd s(a.rows() + l.rows(), a.cols());
    s << a, std::sqrt(alpha) * l;
    dense_ = std::make_unique<Eigen::ColPivHouseholderQR<Eigen::MatrixXd>>(s);
  }
  StackedQr(const SpMat& a, const SpMat& l, double alpha) : m_(a.rows()), n_(a.cols()) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<size_t>(a.nonZeros() + l.nonZeros()));
    for (int k = 0; k < a.outerSize(); ++k)
      for (SpMat::InnerIterator it(a, k); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
    const double root = std::sqrt(alpha);
    for (int k = 0; k < l.outerSize(); ++k)
      for (SpMat::InnerIterator it(l, k); it; ++it) t.emplace_back(a.rows() + it.row(), it.col(), root * it.value());
    SpMat s(a.rows() + l.rows(), a.cols());
    s.setFromTriplets(t.begin(), t.end());
    s.makeCompressed();
    sparse_ = std::make_unique<Eigen::SparseQR<SpMat, Eigen::COLAMDOrdering<int>>>(s);
  }
  // Empty when the factorization failed or R is singular (a zero pivot).
  std::string failure() const {
    if (sparse_ && sparse_->info() != Eigen::Success) return "sparse QR failed: " + sparse_->lastErrorMessage();
    if (!(diagonal().minCoeff() > 0)) return std::string(dense_ ? "Householder QR" : "sparse QR") + ": R has a zero pivot";
    return "";
  }
  // min |R_ii| / max |R_ii|: with column pivoting (dense) an estimate of 1/κ; with COLAMD (sparse) a cruder one,
  // like CHOLMOD's min/max diag(L), but of the stacked matrix (unsquared).
  double rcond() const {
    const Eigen::VectorXd d = diagonal();
    return d.size() == 0 ? 0.0 : d.minCoeff() / d.maxCoeff();
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dense_ ? dense_->rows() : sparse_->rows());
    rhs.head(b.size()) = b;
    return dense_ ? Eigen::VectorXd(dense_->solve(rhs)) : Eigen::VectorXd(sparse_->solve(rhs));
  }
  // trace(A (AᵀA + α LᵀL)⁻¹ Aᵀ) = ‖R⁻ᵀ (A P)ᵀ‖²_F.
  double influence_trace(const Eigen::MatrixXd& a) const {
    Eigen::MatrixXd apt = (a * dense_->colsPermutation()).transpose();
    dense_->matrixR().topLeftCorner(n_, n_).triangularView<Eigen::Upper>().transpose().solveInPlace(apt);
    return apt.squaredNorm();
  }
  double influence_trace(const SpMat& a) const {
    Eigen::MatrixXd apt = Eigen::MatrixXd(SpMat(a * sparse_->colsPermutation()).transpose());
    const SpMat rt = SpMat(sparse_->matrixR().topLeftCorner(n_, n_)).transpose();
    rt.triangularView<Eigen::Lower>().solveInPlace(apt);
    return apt.squaredNorm();
  }

 private:
  Eigen::VectorXd diagonal() const {
    if (dense_) return dense_->matrixR().diagonal().cwiseAbs();
    return SpMat(sparse_->matrixR().topLeftCorner(n_, n_)).diagonal().cwiseAbs();
  }
  Eigen::Index m_, n_;
  std::unique_ptr<Eigen::ColPivHouseholderQR<Eigen::MatrixXd>> dense_;
  std::unique_ptr<Eigen::SparseQR<SpMat, Eigen::COLAMDOrdering<int>>> sparse_;
};

// The dual form of the least-squares problem with C = I: x = Aᵀ y, (AAᵀ + αI) y = b, by one Cholesky factor.
class DualSystem {
 public:
  DualSystem(const Eigen::MatrixXd& a, double alpha) {
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(a.rows(), a.rows());
    g.selfadjointView<Eigen::Lower>().rankUpdate(a);
    // ‖A‖² = the largest eigenvalue of AAᵀ (the m × m tridiagonalisation, not an SVD of A).
    if (g.size() > 0)
      norm2_squared_ = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(g, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
    g.diagonal().array() += alpha;
    llt_.compute(g);
    if (llt_.info() != Eigen::Success) {
      issue_ = "tikhonov: the dual matrix AA' + alpha I is not positive definite to working precision at alpha = " +
               std::to_string(alpha) + "; use backend spectral";
    } else if (const double rc = llt_.rcond(); !(rc >= 1e-11)) {
      char buf[256];
      std::snprintf(buf, sizeof buf, "tikhonov: the dual matrix AA' + alpha I has reciprocal condition %.3g < 1e-11 at "
                    "alpha = %.3g (x would carry relative errors up to %.1g); use backend spectral", rc, alpha,
                    std::numeric_limits<double>::epsilon() / rc);
      issue_ = buf;
    }
  }
  const std::string& issue() const { return issue_; }
  double norm2_squared() const { return norm2_squared_; }
  Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) const {
    if (!issue_.empty() && llt_.info() != Eigen::Success) return Eigen::MatrixXd::Zero(a.cols(), b.cols());
    return a.transpose() * llt_.solve(b);
  }

 private:
  Eigen::LLT<Eigen::MatrixXd> llt_;
  double norm2_squared_ = 0.0;
  std::string issue_;
};

// The dual form with a first-difference L (each row of L one link: two entries of opposite sign, or one, a link to
// a known zero), for a wide A (m ≪ n): min ‖Ax − b‖² + α‖Lx‖², M = LᵀL sparse. M is singular on each connected
// component of the links that no known-zero link anchors (its indicator spans null(L); N: those indicators,
// normalised). With G = (M + Σ_g e_g e_gᵀ)⁻¹, one node g of each such component grounded (G is a generalized inverse:
// M G v = v for v ⊥ null(M)), the optimality conditions (AᵀA + αM) x = Aᵀb read, with y = (b − Ax)/α,
//   [A G Aᵀ + αI   A N] [y]   [b]
//   [(A N)ᵀ         0 ] [z] = [0],   x = G Aᵀ y + N z,
// the second row being the condition Aᵀy ⊥ null(M) under which M G Aᵀ y = Aᵀ y. Setup: one sparse Cholesky of the
// grounded M (CHOLMOD), m solves for G Aᵀ, an m × m Cholesky and the k × k Schur complement (k = dim null(L)).
class DualDifferenceSystem {
 public:
  DualDifferenceSystem(const Eigen::MatrixXd& a, const SpMat& l, double alpha) {
    const Eigen::Index n = a.cols();
    const auto at = [](Eigen::Index i) { return static_cast<size_t>(i); };
    // The links' components (union-find over the two-entry rows) and the anchored ones (a one-entry row).
    std::vector<Eigen::Index> parent(at(n));
    for (Eigen::Index i = 0; i < n; ++i) parent[at(i)] = i;
    const auto root = [&](Eigen::Index i) {
      while (parent[at(i)] != i) {
        parent[at(i)] = parent[at(parent[at(i)])];
        i = parent[at(i)];
      }
      return i;
    };
    std::vector<std::vector<std::pair<Eigen::Index, double>>> rows(at(l.rows()));  // each row's entries
    for (int k = 0; k < l.outerSize(); ++k)
      for (SpMat::InnerIterator it(l, k); it; ++it)
        if (it.value() != 0.0) rows[at(it.row())].emplace_back(it.col(), it.value());
    std::vector<Eigen::Index> anchored_nodes;
    for (const auto& r : rows) {
      if (r.size() == 1) {
        anchored_nodes.push_back(r[0].first);
      } else if (r.size() == 2 && std::abs(r[0].second + r[1].second) <= 1e-12 * std::abs(r[0].second)) {
        parent[at(root(r[0].first))] = root(r[1].first);
      } else if (!r.empty()) {
        throw ConfigError("/backend", "backend dual serves regularizer identity or a first difference (each row of L "
                                      "one link); use backend spectral");
      }
    }
    std::vector<char> anchored(at(n), 0);
    for (const Eigen::Index i : anchored_nodes) anchored[at(root(i))] = 1;
    std::vector<Eigen::Index> component(at(n), -1), column_of(at(n), -1), ground;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index r = root(i);
      if (anchored[at(r)]) continue;
      if (column_of[at(r)] < 0) {
        column_of[at(r)] = static_cast<Eigen::Index>(ground.size());
        ground.push_back(i);
      }
      component[at(i)] = column_of[at(r)];
    }
    const auto k = static_cast<Eigen::Index>(ground.size());
    Eigen::VectorXd size = Eigen::VectorXd::Zero(k);
    for (const Eigen::Index c : component)
      if (c >= 0) size(c) += 1.0;
    // N's columns: the components' indicators over √size.
    null_ = Eigen::MatrixXd::Zero(n, k);
    for (Eigen::Index i = 0; i < n; ++i)
      if (const Eigen::Index c = component[at(i)]; c >= 0) null_(i, c) = 1.0 / std::sqrt(size(c));
    SpMat grounded = SpMat(l.transpose() * l);
    for (const Eigen::Index g : ground) grounded.coeffRef(g, g) += 1.0;
    grounded.makeCompressed();
    Cholmod chol;
    chol.compute(grounded);
    if (chol.info() != Eigen::Success || !(chol.rcond() >= singular_rcond)) {
      issue_ = "tikhonov: the grounded regularizer L'L is singular to working precision; use backend spectral";
      return;
    }
    g_at_ = chol.solve(Eigen::MatrixXd(a.transpose()));
    Eigen::MatrixXd kk = a * g_at_;
    kk = 0.5 * (kk + kk.transpose()).eval();
    kk.diagonal().array() += alpha;
    llt_.compute(kk);
    if (llt_.info() != Eigen::Success) {
      issue_ = "tikhonov: the dual matrix A G A' + alpha I is not positive definite to working precision; use backend "
               "spectral";
      return;
    }
    if (const double rc = llt_.rcond(); !(rc >= 1e-11)) {
      char buf[256];
      std::snprintf(buf, sizeof buf, "tikhonov: the dual matrix A G A' + alpha I has reciprocal condition %.3g < 1e-11 at "
                    "alpha = %.3g; use backend spectral", rc, alpha);
      issue_ = buf;
    }
    if (k == 0) return;
    an_ = a * null_;
    kinv_an_ = llt_.solve(an_);
    schur_.compute(an_.transpose() * kinv_an_);
    if (!(schur_.rcond() >= 1e-12))
      issue_ = "tikhonov: the data do not determine the mean of a component of the reconstruction that the "
               "regularizer leaves free (A N is rank-deficient); use backend spectral";
  }
  const std::string& issue() const { return issue_; }
  Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& b) const {
    if (g_at_.size() == 0 || llt_.info() != Eigen::Success) return Eigen::MatrixXd::Zero(null_.rows(), b.cols());
    Eigen::MatrixXd t = llt_.solve(b);
    if (null_.cols() == 0) return g_at_ * t;
    const Eigen::MatrixXd z = schur_.solve(an_.transpose() * t);
    t -= kinv_an_ * z;
    return g_at_ * t + null_ * z;
  }

 private:
  Eigen::MatrixXd null_, g_at_, an_, kinv_an_;  // N, G Aᵀ, A N, (A G Aᵀ + αI)⁻¹ A N
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::LDLT<Eigen::MatrixXd> schur_;
  std::string issue_;
};

}  // namespace closurelab::tikhonov_detail
