#include "strategies/deconvolution/standard_form.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <limits>
#include <string>

#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"

namespace closurelab {

StandardForm::StandardForm(const ForwardOperator& a, const Eigen::SparseMatrix<double>& l) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const Eigen::MatrixXd ad = a.to_dense();
  const Eigen::Index m = ad.rows(), n = ad.cols();
  if (l.cols() != n)
    throw ConfigError("/regularizer", "the regularizer has " + std::to_string(l.cols()) + " columns for " +
                                          std::to_string(n) + " unknowns");
  // L = U_L diag(s) V_Lᵀ: its numerical rank r, L̃† = V_r diag(1/s_r), and W = null(L).
  const Eigen::BDCSVD<Eigen::MatrixXd> lsvd(Eigen::MatrixXd(l), Eigen::ComputeFullV);
  const Eigen::VectorXd& s = lsvd.singularValues();
  const double ltol = static_cast<double>(std::max<Eigen::Index>(l.rows(), n)) * eps * (s.size() > 0 ? s(0) : 0.0);
  Eigen::Index r = 0;
  while (r < s.size() && s(r) > ltol) ++r;
  Eigen::MatrixXd lap = lsvd.matrixV().leftCols(r) * s.head(r).cwiseInverse().asDiagonal();  // L̃†, then L_A†
  w_ = lsvd.matrixV().rightCols(n - r);
  Eigen::MatrixXd abar = ad * lap;  // A L̃†, then Ā = P⊥ A L̃†
  if (w_.cols() > 0) {
    aw_ = ad * w_;
    aw_qr_.compute(aw_);
    // AW must have full column rank, else some x in null(L) has A x ≈ 0 and ‖Ax − b‖² + α‖Lx‖² has no unique
    // minimizer. Column pivoting orders |R_ii|: the last one estimates σ_min(AW) (W has orthonormal columns).
    const double rmin = aw_qr_.matrixR().diagonal().cwiseAbs().minCoeff();
    if (!(rmin > static_cast<double>(std::max(m, n)) * eps * ad.norm()))
      throw ConfigError("/regularizer", "the operator maps a vector of the regularizer's null space to zero (|R_kk| = " +
                                            std::to_string(rmin) +
                                            "): the null spaces of A and L intersect and the Tikhonov solution is not unique");
    const Eigen::MatrixXd z = aw_qr_.solve(abar);  // (AW)† A L̃†
    abar -= aw_ * z;
    lap -= w_ * z;
  }
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(abar, Eigen::ComputeThinU | Eigen::ComputeThinV);
  u_ = svd.matrixU();
  sigma_ = svd.singularValues();
  m_ = lap * svd.matrixV();
  if (sigma_.size() > 0) rank_tolerance_ = static_cast<double>(std::max(m, r)) * eps * sigma_(0);
}

StandardForm::Data StandardForm::data(const Eigen::VectorXd& b) const {
  Data d;
  Eigen::VectorXd bbar = b;
  d.x0 = Eigen::VectorXd::Zero(m_.rows());
  if (w_.cols() > 0) {
    const Eigen::VectorXd z = aw_qr_.solve(b);
    d.x0 = w_ * z;
    bbar -= aw_ * z;
  }
  d.beta = u_.transpose() * bbar;
  // b̄ lies in range(P⊥), of dimension m − (n − r); only when Ū has fewer columns can part of it be out of reach.
  if (u_.rows() - w_.cols() > u_.cols()) d.outside2 = (bbar - u_ * d.beta).squaredNorm();
  return d;
}

double StandardForm::filter(Eigen::Index i, double alpha) const {
  const double s = sigma_(i);
  if (s <= rank_tolerance_) return 0.0;
  return s / (s * s + alpha);
}

Eigen::VectorXd StandardForm::solution(const Data& d, double alpha) const {
  Eigen::VectorXd c(d.beta.size());
  for (Eigen::Index i = 0; i < c.size(); ++i) c(i) = filter(i, alpha) * d.beta(i);
  return d.x0 + m_ * c;
}

}  // namespace closurelab
