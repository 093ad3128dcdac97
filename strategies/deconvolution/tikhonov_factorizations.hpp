#pragma once
// The factorisations behind Tikhonov's backends (tikhonov.cpp): CHOLMOD with its condition estimate (the paper
// form, sparse), the stacked QR of [A; √α L] (the least-squares form, dense and sparse) and the dual system
// AAᵀ + αI by Cholesky (backend dual).
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

}  // namespace closurelab::tikhonov_detail
