#pragma once
// The SPH pair force (5.1), with Morris's viscous term written with (μ_i + μ_j) (the seed prints ½μ; with
// the sum the continuum limit is μ∇²v, which the Poiseuille tests confirm): the force on particle i due
// to particle j,
//   f_ij = −(P_i/n_i² + P_j/n_j²) ∇_i w + (μ_i + μ_j) (v_i − v_j) (q_ij·∇_i w) / (n_i n_j |q_ij|²),
// with ∇_i w = F q_ij, F = w'(r)/r, q_ij = q_i − q_j, so (q_ij·∇_i w)/|q_ij|² = F.
// One definition, used by the direct SPH engine and by the stress quadratures.
#include "core/mesh.hpp"

namespace closurelab {

inline Vec2 sph_pair_force(double p_over_n2_i, double p_over_n2_j, double mu_i, double mu_j, double n_i, double n_j,
                           double F, const Vec2& q_ij, const Vec2& v_ij) {
  return -(p_over_n2_i + p_over_n2_j) * F * q_ij + (mu_i + mu_j) * F / (n_i * n_j) * v_ij;
}

}  // namespace closurelab
