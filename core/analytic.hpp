#pragma once
// Analytic steady solutions and their Gaussian averages (§5.2, Appendices B and D).
#include <functional>

namespace closurelab {

// (5.15): Poiseuille flow between walls at l1 and l2 under a uniform force g; zero outside [l1, l2].
double poiseuille_velocity(double y, double l1, double l2, double rho, double g, double mu);

// (D.3): the same channel under the force g [1 + A sin(nπ (y − l1)/(l2 − l1))]; zero outside [l1, l2].
double periodic_force_velocity(double y, double l1, double l2, double rho, double g, double mu, double amplitude,
                               double n);

// (B.2): the Gaussian average (window η) of the parabola of (5.15) continued beyond the walls.
double poiseuille_averaged_b2(double y, double l1, double l2, double rho, double g, double mu, double eta);

// Appendix B: −T_c,xx/ρ at steady state for the continued parabola (the covariance of V under the window).
double poiseuille_convective_stress_b(double y, double l1, double l2, double rho, double g, double mu, double eta);

// ∫ φ(y − y') f(y') dy' over [lo, hi] (f taken as zero outside), for a 1D window φ of numerical support
// `radius`, by GSL adaptive quadrature (relative accuracy ~1e-12). For an f defined on the whole line
// (periodic scenes) pass lo = y − radius, hi = y + radius.
double average_by_quadrature(const std::function<double(double)>& f, const std::function<double(double)>& phi,
                             double radius, double y, double lo, double hi);

}  // namespace closurelab
