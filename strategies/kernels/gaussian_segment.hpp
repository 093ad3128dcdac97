#pragma once
// The Gaussian line integral behind the bond integral of Appendix A, in a numerically stable form.
#include "core/base/mesh.hpp"

namespace closurelab {

// ∫_{s0}^{s1} exp(−|a − s d|² / η²) ds for 2D vectors a, d (unnormalized).
// Appendix A writes it as a difference of erf values, which cancels catastrophically away from the
// bond's closest point. Here: where the exponent varies by less than 1 over [s0, s1], fixed
// Gauss–Legendre quadrature (the integrand is then nearly constant, and |d| → 0 is covered);
// where the interval straddles the closest point, erf(u1) + erf(−u0) (no cancellation); otherwise the
// difference of exp(−E) erfcx(u) terms, whose ratio is ≤ e^{−1}, so at most ~1.6× round-off is lost.
double gaussian_segment_integral(const Vec2& a, const Vec2& d, double s0, double s1, double eta);

// erfcx(x) = exp(x²) erfc(x) for x >= 0, from GSL's hazard function (no overflow, full precision).
double erfcx(double x);

}  // namespace closurelab
