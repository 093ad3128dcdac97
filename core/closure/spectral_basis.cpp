#include "core/closure/spectral_basis.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <limits>
#include <numeric>

#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"

namespace closurelab {

namespace {
void decompose(const Eigen::MatrixXd& a, SpectralBasis::Kind kind, Eigen::MatrixXd& u, Eigen::MatrixXd& v,
               Eigen::VectorXd& s) {
  if (kind == SpectralBasis::Kind::svd) {
    Eigen::BDCSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
    u = svd.matrixU();
    v = svd.matrixV();
    s = svd.singularValues();
  } else {
    if (a.rows() != a.cols()) throw ConfigError("", "a symmetric eigendecomposition needs a square operator");
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (a + a.transpose()));
    u = eig.eigenvectors();
    v = u;
    s = eig.eigenvalues();
  }
}
}  // namespace

SpectralBasis::SpectralBasis(const ForwardOperator& a, Kind kind) : kind_(kind), m_(a.rows()) {
  if (kind == Kind::symmetric_eigen && !a.is_symmetric(1e-10))
    throw ConfigError("", "the paper's form (A + alpha C) x = b with a spectral solve needs a symmetric A");
  if (a.storage() == OperatorStorage::kronecker) {
    kronecker_ = true;
    Eigen::VectorXd sx, sy;
    decompose(a.factor_x(), kind, ux_, vx_, sx);
    decompose(a.factor_y(), kind, uy_, vy_, sy);
    sigma_.resize(sx.size() * sy.size());
    for (Eigen::Index j = 0; j < sy.size(); ++j) sigma_.segment(j * sx.size(), sx.size()) = sy(j) * sx;
  } else {
    decompose(a.to_dense(), kind, u_, v_, sigma_);
  }
  order_.resize(sigma_.size());
  std::iota(order_.data(), order_.data() + order_.size(), 0);
  std::stable_sort(order_.data(), order_.data() + order_.size(),
                   [this](int p, int q) { return std::abs(sigma_(p)) > std::abs(sigma_(q)); });
  if (sigma_.size() > 0) {
    rank_tolerance_ = static_cast<double>(std::max<Eigen::Index>(m_, a.cols())) * std::numeric_limits<double>::epsilon() *
                      std::abs(sigma_(order_(0)));
    while (numerical_rank_ < sigma_.size() && std::abs(sigma_(order_(numerical_rank_))) > rank_tolerance_) ++numerical_rank_;
  }
}

Eigen::VectorXd SpectralBasis::coefficients(const Eigen::VectorXd& b) const {
  if (!kronecker_) return u_.transpose() * b;
  Eigen::Map<const Eigen::MatrixXd> B(b.data(), ux_.rows(), uy_.rows());
  Eigen::VectorXd c(ux_.cols() * uy_.cols());
  Eigen::Map<Eigen::MatrixXd> C(c.data(), ux_.cols(), uy_.cols());
  C.noalias() = (ux_.transpose() * B) * uy_;
  return c;
}

Eigen::VectorXd SpectralBasis::synthesize(const Eigen::VectorXd& c) const {
  if (!kronecker_) return v_ * c;
  Eigen::Map<const Eigen::MatrixXd> C(c.data(), vx_.cols(), vy_.cols());
  Eigen::VectorXd x(vx_.rows() * vy_.rows());
  Eigen::Map<Eigen::MatrixXd> X(x.data(), vx_.rows(), vy_.rows());
  X.noalias() = (vx_ * C) * vy_.transpose();
  return x;
}

Eigen::MatrixXd SpectralBasis::coefficients(const Eigen::MatrixXd& b) const {
  if (!kronecker_) return u_.transpose() * b;
  Eigen::MatrixXd c(ux_.cols() * uy_.cols(), b.cols());
  for (Eigen::Index k = 0; k < b.cols(); ++k) c.col(k) = coefficients(Eigen::VectorXd(b.col(k)));
  return c;
}

Eigen::MatrixXd SpectralBasis::synthesize(const Eigen::MatrixXd& c) const {
  if (!kronecker_) return v_ * c;
  Eigen::MatrixXd x(vx_.rows() * vy_.rows(), c.cols());
  for (Eigen::Index k = 0; k < c.cols(); ++k) x.col(k) = synthesize(Eigen::VectorXd(c.col(k)));
  return x;
}

}  // namespace closurelab
