#pragma once
// The averaging-kernel strategy family (DESIGN.md §2): the window ψ_η of (2.6)–(2.7), its Fourier symbol,
// its support and the bond integral of Appendix A. All built-in kernels are separable,
// ψ(x, y) = φ(x) φ(y), which the forward operators of the deconvolution use (A = A_y ⊗ A_x).
#include <cmath>
#include <string>

#include "core/base/mesh.hpp"

namespace closurelab {

class AveragingKernel {
 public:
  virtual ~AveragingKernel() = default;

  virtual std::string name() const = 0;
  // η' (the length scale of the window).
  virtual double eta() const = 0;
  // The 1D factor φ with ψ(x, y) = φ(x) φ(y); ∫ φ = 1.
  virtual double factor(double t) const = 0;
  // Its derivative φ'(t) (the convective flux's divergence, core/reduced/force_density_2d.hpp).
  virtual double factor_derivative(double t) const = 0;
  // Fourier symbol of the 1D factor, ∫ φ(t) e^{-2πiξt} dt (real, the factor is even).
  virtual double factor_symbol(double xi) const = 0;
  // Radius beyond which φ is zero or negligible against its peak (below ~1e-15 of it: the Gaussian's 6η gives
  // exp(−36) ≈ 2.3e-16), per coordinate: the numerical support.
  virtual double support_radius() const = 0;
  // Appendix A: ∫₀¹ ψ(s(x − q_k) + (1 − s)(x − q_j)) ds, for the bond from q_j to q_k.
  virtual double bond_integral(const Vec2& x, const Vec2& qj, const Vec2& qk) const = 0;

  // ψ(r) in 2D.
  double value(const Vec2& r) const { return factor(r.x()) * factor(r.y()); }
  // 2D Fourier symbol (4.15 for the Gaussian): ψ̂(ξ) = φ̂(ξ_x) φ̂(ξ_y).
  double symbol(const Vec2& xi) const { return factor_symbol(xi.x()) * factor_symbol(xi.y()); }
};

// φ(d) summed over the periodic images of the displacement d along `axis` (φ(d) itself on a non-periodic axis):
// the one image sum of the forward operators and the reconstruction.
inline double factor_over_images(const AveragingKernel& k, const UniformMesh1D& axis, double d) {
  if (!axis.periodic) return k.factor(d);
  const double p = axis.period;
  d -= p * std::round(d / p);
  const int images = static_cast<int>(std::ceil(k.support_radius() / p)) + 1;
  double v = 0;
  for (int q = -images; q <= images; ++q) v += k.factor(d + q * p);
  return v;
}

// φ'(d) summed over the periodic images, as factor_over_images.
inline double factor_derivative_over_images(const AveragingKernel& k, const UniformMesh1D& axis, double d) {
  if (!axis.periodic) return k.factor_derivative(d);
  const double p = axis.period;
  d -= p * std::round(d / p);
  const int images = static_cast<int>(std::ceil(k.support_radius() / p)) + 1;
  double v = 0;
  for (int q = -images; q <= images; ++q) v += k.factor_derivative(d + q * p);
  return v;
}

}  // namespace closurelab
