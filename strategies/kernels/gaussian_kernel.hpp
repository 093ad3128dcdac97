#pragma once
#include "core/averaging/averaging_kernel.hpp"

namespace closurelab {

// The Gaussian window (2.7) in 2D: ψ_η(x) = exp(−|x|²/η²) / (π η²) = φ(x) φ(y), φ(t) = exp(−t²/η²)/(√π η).
class GaussianKernel : public AveragingKernel {
 public:
  explicit GaussianKernel(double eta);
  std::string name() const override { return "gaussian"; }
  double eta() const override { return eta_; }
  double factor(double t) const override;
  double factor_derivative(double t) const override;  // −2t/η² φ(t)
  double factor_symbol(double xi) const override;  // exp(−π² η² ξ²), cf. (4.15)
  double support_radius() const override { return 6.0 * eta_; }  // exp(−36) ≈ 2.3e-16
  double bond_integral(const Vec2& x, const Vec2& qj, const Vec2& qk) const override;

 private:
  double eta_;
};

// A Gaussian truncated to the box |x|, |y| <= r_c and renormalized: φ_c(t) = φ(t) / erf(r_c/η) on |t| <= r_c.
// Separable like the Gaussian; sampled, it can have negative eigenvalues when r_c is 2–3 σ (σ = η/√2).
class CutoffGaussianKernel : public AveragingKernel {
 public:
  CutoffGaussianKernel(double eta, double cutoff_in_eta);
  std::string name() const override { return "cutoff_gaussian"; }
  double eta() const override { return eta_; }
  double factor(double t) const override;
  double factor_derivative(double t) const override;  // −2t/η² φ_c(t) inside the box (φ_c jumps at ±r_c)
  double factor_symbol(double xi) const override;  // by GSL adaptive quadrature
  double support_radius() const override { return rc_; }
  double bond_integral(const Vec2& x, const Vec2& qj, const Vec2& qk) const override;

 private:
  double eta_, rc_, z_;
};

}  // namespace closurelab
