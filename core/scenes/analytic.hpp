#pragma once
// Analytic steady solutions and their Gaussian averages (§5.2, Appendices B and D).
#include <functional>
#include <vector>

#include "core/base/mesh.hpp"

namespace closurelab {

// (5.15): Poiseuille flow between walls at l1 and l2 under a uniform force g; zero outside [l1, l2].
double poiseuille_velocity(double y, double l1, double l2, double rho, double g, double mu);

// (D.3): the same channel under the force g [1 + A sin(nπ (y − l1)/(l2 − l1))]; zero outside [l1, l2].
double periodic_force_velocity(double y, double l1, double l2, double rho, double g, double mu, double amplitude,
                               double n);

// §7: steady layered flow between walls at l1 and l2 under a uniform force g, with a piecewise-constant
// viscosity: d/dy(μ(y) dv/dy) = −ρg, v(l1) = v(l2) = 0. Integrating once, μ v' = C − ρg (y − l1) (the shear
// stress is continuous across the interfaces), so
//   v(y) = ∫_{l1}^{y} (C − ρg (s − l1)) / μ(s) ds,   C from v(l2) = 0,
// a parabola in each layer, evaluated in closed form. `interfaces` are ascending heights strictly inside
// (l1, l2); `viscosity` holds one value per segment (interfaces.size() + 1), from l1 upwards. Zero outside
// [l1, l2]. With no interfaces it is (5.15).
class LayeredChannelFlow {
 public:
  LayeredChannelFlow(double l1, double l2, std::vector<double> interfaces, std::vector<double> viscosity, double rho,
                     double g);
  double velocity(double y) const;
  double shear_stress(double y) const { return shear_at_l1_ - rho_g_ * (y - l1_); }  // μ v' = C − ρg (y − l1)
  double viscosity(double y) const;
  // The maximum of |v| (at y* = l1 + C/(ρg), where the shear stress vanishes) and its height.
  double peak() const { return std::abs(velocity(peak_height())); }
  double peak_height() const;

 private:
  std::size_t segment(double y) const;
  double l1_, l2_, rho_g_, shear_at_l1_ = 0.0;
  std::vector<double> start_, mu_, v_start_;  // per segment: lower edge, viscosity, velocity at the lower edge
};

// Cellular flow in a doubly periodic box, k = 2π m / L (m cells per side): the divergence-free unit mode
// (sin kx cos ky, −cos kx sin ky), an eigenfunction of the Laplacian with eigenvalue −2k². Under the body force
// g · mode the steady Stokes velocity is A · mode with A = g / (2 k² ν); it is also the steady Navier–Stokes
// velocity, the inertial term ρ (v·∇)v being balanced by the pressure below. From an initial A0 · mode, the
// velocity stays a multiple of the mode: A(t) = A + (A0 − A) e^{−2k²νt}.
Vec2 cellular_mode(double x, double y, double k);
// p = ρ A² (cos 2kx + cos 2ky) / 4 (up to a constant), so that ρ (v·∇)v = −∇p for v = A · mode.
double cellular_pressure(double x, double y, double k, double rho, double amplitude);

// (B.2): the Gaussian average (window η) of the parabola of (5.15) continued beyond the walls.
double poiseuille_averaged_b2(double y, double l1, double l2, double rho, double g, double mu, double eta);

// Appendix B: −T_c,xx/ρ at steady state for the continued parabola (the covariance of V under the window).
double poiseuille_convective_stress_b(double y, double l1, double l2, double rho, double g, double mu, double eta);

// ∫ φ(y − y') f(y') dy' over [lo, hi] (f taken as zero outside), for a 1D window φ of numerical support
// `radius`, by GSL adaptive quadrature (relative accuracy ~1e-12). For an f defined on the whole line
// (periodic scenes) pass lo = y − radius, hi = y + radius. `breakpoints` are heights where f has a kink or a
// jump (the interfaces of a layered flow): the integral is split there.
double average_by_quadrature(const std::function<double(double)>& f, const std::function<double(double)>& phi,
                             double radius, double y, double lo, double hi,
                             const std::vector<double>& breakpoints = {});

}  // namespace closurelab
