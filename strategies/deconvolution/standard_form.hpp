#pragma once
// General-form Tikhonov, min ‖A x − b‖² + α ‖L x‖², for every α from one transformation to standard form and one
// SVD (Eldén 1982; Hansen, "Rank-Deficient and Discrete Ill-Posed Problems" §2.3, Regularization Tools `std_form`):
// the filter factors of the generalized SVD of (A, L), without forming AᵀA + α LᵀL (which squares the
// condition number).
//   L = U_L diag(s) V_Lᵀ (an SVD of L, numerical rank r): ‖L x‖ = ‖L̃ x‖ with L̃ = diag(s_r) V_rᵀ (r × n, full row
//   rank; L may have any shape); W = the other n − r columns of V_L spans null(L); AW = Q_w R_w (column-pivoted QR).
//   x = x₀ + L_A† ȳ, x₀ = W (AW)† b (the part in null(L), which α does not damp), L_A† = (I − W (AW)† A) L̃†
//   (the A-weighted pseudo-inverse of L); then ‖A x − b‖ = ‖Ā ȳ − b̄‖ and ‖L x‖ = ‖ȳ‖, with
//   Ā = A L_A† = P⊥ A L̃† and b̄ = P⊥ b, P⊥ = I − Q_w Q_wᵀ.
//   Ā = Ū diag(σ̄) V̄ᵀ (thin SVD): x(α) = x₀ + M diag(φ_i) β̄, β̄ = Ūᵀ b̄, M = L_A† V̄, φ_i = σ̄_i / (σ̄_i² + α);
//   ‖b − A x‖² = Σ ((1 − f_i) β̄_i)² + ‖b̄ − Ū β̄‖², f_i = σ̄_i² / (σ̄_i² + α); ‖L x‖² = Σ (φ_i β̄_i)²; the
//   influence matrix A A^#(α) has trace (n − r) + Σ f_i (its null-space part is a projection of rank n − r).
// A dense or Kronecker operator is used as a dense matrix: setup costs O((m + p) n²) and two SVDs, each α O(m n).
// Values σ̄_i <= max(m, r) ε σ̄_1 are zero to working precision and filtered out (as SpectralBasis does).
#include <Eigen/Core>
#include <Eigen/QR>
#include <Eigen/SparseCore>

namespace closurelab {

class ForwardOperator;

class StandardForm {
 public:
  // What one right-hand side contributes, computed once for all α.
  struct Data {
    Eigen::VectorXd beta;    // β̄ = Ūᵀ b̄
    Eigen::VectorXd x0;      // x₀ = W (AW)† b
    double outside2 = 0.0;   // ‖b̄ − Ū β̄‖², the residual no α removes
  };
  StandardForm() = default;
  // Throws ConfigError("/regularizer") when null(A) and null(L) intersect (the minimizer is not unique).
  StandardForm(const ForwardOperator& a, const Eigen::SparseMatrix<double>& l);

  const Eigen::VectorXd& sigma() const { return sigma_; }  // σ̄, decreasing
  double rank_tolerance() const { return rank_tolerance_; }
  Eigen::Index null_dimension() const { return w_.cols(); }  // n − r
  Data data(const Eigen::VectorXd& b) const;
  double filter(Eigen::Index i, double alpha) const;  // φ_i (0 below the rank tolerance)
  Eigen::VectorXd solution(const Data& d, double alpha) const;

 private:
  Eigen::MatrixXd u_, m_, w_, aw_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> aw_qr_;
  Eigen::VectorXd sigma_;
  double rank_tolerance_ = 0.0;
};

}  // namespace closurelab
