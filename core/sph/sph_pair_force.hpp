#pragma once
// The SPH pair force (5.1), with Morris's viscous term written with the pair viscosity μ_ij (the seed prints
// ½μ; with μ_ij = μ_i + μ_j the continuum limit is μ∇²v, which the Poiseuille tests confirm): the force on
// particle i due to particle j,
//   f_ij = −(P_i/n_i² + P_j/n_j²) ∇_i w + μ_ij (v_i − v_j) (q_ij·∇_i w) / (n_i n_j |q_ij|²),
// with ∇_i w = F q_ij, F = w'(r)/r, q_ij = q_i − q_j, so (q_ij·∇_i w)/|q_ij|² = F.
// One definition, used by the direct SPH engine and by the stress quadratures.
#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "core/base/enum_names.hpp"
#include "core/base/mesh.hpp"

namespace closurelab {

// How the pair viscosity μ_ij of (5.1) combines unlike particles (two-phase flow, §7). Both give 2μ for like
// particles, so single-phase results do not depend on the choice.
enum class PairViscosityMean {
  arithmetic,  // μ_ij = μ_i + μ_j (twice the arithmetic mean; Morris et al. 1997)
  harmonic,    // μ_ij = 4 μ_i μ_j / (μ_i + μ_j) (twice the harmonic mean; continuous viscous flux across a
               // viscosity jump, as in finite-volume schemes)
};

template <>
struct EnumNames<PairViscosityMean> {
  static constexpr std::array<std::pair<PairViscosityMean, std::string_view>, 2> table{
      {{PairViscosityMean::arithmetic, "arithmetic"}, {PairViscosityMean::harmonic, "harmonic"}}};
};

// μ_ij of (5.1). Like particles take exactly μ_i + μ_j = 2μ under either mean (bitwise: single-phase runs do
// not change with the option).
inline double pair_viscosity(double mu_i, double mu_j, PairViscosityMean mean) {
  if (mean == PairViscosityMean::arithmetic || mu_i == mu_j) return mu_i + mu_j;
  return 4.0 * mu_i * mu_j / (mu_i + mu_j);
}

// (5.1) in components, the one definition: p_sum = P_i/n_i² + P_j/n_j², visc = μ_ij / (n_i n_j). The engine's
// pair loop calls it with reciprocals 1/n taken once per particle.
inline void sph_pair_force(double p_sum, double visc, double F, double qx, double qy, double vx, double vy, double& fx,
                           double& fy) {
  const double a = -p_sum * F, b = visc * F;
  fx = a * qx + b * vx;
  fy = a * qy + b * vy;
}

inline Vec2 sph_pair_force(double p_over_n2_i, double p_over_n2_j, double mu_ij, double n_i, double n_j, double F,
                           const Vec2& q_ij, const Vec2& v_ij) {
  double fx, fy;
  sph_pair_force(p_over_n2_i + p_over_n2_j, mu_ij / (n_i * n_j), F, q_ij.x(), q_ij.y(), v_ij.x(), v_ij.y(), fx, fy);
  return {fx, fy};
}

}  // namespace closurelab
