#pragma once
// A spectral decomposition of a forward operator for filter-factor methods (truncated SVD, Tikhonov with
// C = I, §4.2): A = U diag(σ) Vᵀ (SVD) or, for the paper's Tikhonov form (4.7) on a symmetric A, A = Q diag(λ) Qᵀ
// (eigen, σ = λ may be negative). Dense operators use Eigen's BDCSVD / SelfAdjointEigenSolver; Kronecker
// operators A = A_y ⊗ A_x decompose their factors only, so setup costs O(n_x³ + n_y³) and a solve two small
// matrix products per factor (DESIGN.md §6).
//
// A filtered solution is x = V diag(φ_i) β with β = Uᵀ b; the residual is ‖b − A x‖² = Σ((1 − σ_i φ_i) β_i)²
// + ‖b_⊥‖², b_⊥ the part of b outside range(U).
#include <Eigen/Core>

namespace closurelab {

class ForwardOperator;

class SpectralBasis {
 public:
  enum class Kind { svd, symmetric_eigen };
  SpectralBasis() = default;
  SpectralBasis(const ForwardOperator& a, Kind kind);

  Kind kind() const { return kind_; }
  // σ_i (or λ_i) in the basis' own order; `order()` lists indices by decreasing |σ|.
  const Eigen::VectorXd& sigma() const { return sigma_; }
  const Eigen::VectorXi& order() const { return order_; }
  Eigen::Index data_size() const { return m_; }
  // Singular values with |σ| <= max(m, n) ε |σ_1| are zero to working precision; filter methods drop them
  // (otherwise GCV sees spurious minima at the noise-fitting end of the family).
  double rank_tolerance() const { return rank_tolerance_; }
  int numerical_rank() const { return numerical_rank_; }

  Eigen::VectorXd coefficients(const Eigen::VectorXd& b) const;   // β = Uᵀ b
  Eigen::VectorXd synthesize(const Eigen::VectorXd& c) const;     // V c
  Eigen::MatrixXd coefficients(const Eigen::MatrixXd& b) const;   // the same for every column
  Eigen::MatrixXd synthesize(const Eigen::MatrixXd& c) const;

 private:
  Kind kind_ = Kind::svd;
  bool kronecker_ = false;
  Eigen::Index m_ = 0;
  Eigen::MatrixXd u_, v_, ux_, vx_, uy_, vy_;  // dense: u_, v_; Kronecker: per factor
  Eigen::VectorXd sigma_;
  Eigen::VectorXi order_;
  double rank_tolerance_ = 0.0;
  int numerical_rank_ = 0;
};

}  // namespace closurelab
