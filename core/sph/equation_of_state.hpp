#pragma once
// Equations of state of the direct SPH model. One definition of each, used by the engine
// (core/sph/sph_engine.cpp) and by the stress quadratures.
//
// Weakly compressible (single-phase scenes, the default): P = c² (m n − ρ0) + P_b.
//
// Van der Waals (7.1), two-phase flow (§7): P_i = n_i k_B T / (1 − c_1 n_i) − k_ij c_2 n_i², with k_ij = 1 for
// like particles (wall particles count as the phase they carry) and k* < 1 across phases. In the pair force
// (5.1) both P_i/n_i² and P_j/n_j² take the pair's k_ij, and since the attraction term of (7.1) over n² is the
// constant k_ij c_2, an unlike pair carries the like pair's P_i/n_i² + P_j/n_j² plus 2 (1 − k*) c_2: an extra
// repulsion between the phases (the paper's surface tension, which grows as k* falls).
//
// Parametrization (ours; the paper gives no values). With the lattice number density n0 and m = ρ0/n0, write
// c_1 n0 = φ and c_2 n0 = a k_B T. Then, for like particles, with x = n/n0,
//   P(x)  = n0 k_B T [x / (1 − φ x) − a x²],
//   dP/dn = k_B T [1 / (1 − φ x)² − 2 a x],
// and at the rest state x = 1
//   P(n0) > 0     ⇔ a < 1 / (1 − φ)            (no tensile instability at rest),
//   dP/dn(n0) > 0 ⇔ a < 1 / (2 (1 − φ)²)       (mechanically stable liquid),
// so 0 <= a < a_max(φ) = min(1/(1 − φ), 1/(2 (1 − φ)²)) with 0 < φ < 1 (n < n0/φ is the close-packing limit).
// The sound speed c² = dP/dρ = (1/m) dP/dn at n0 fixes the temperature:
//   k_B T = m c² / (1/(1 − φ)² − 2a).
// The unlike-pair excess pressure ("interface pressure jump") is (1 − k*) c_2 n0² = (1 − k*) a n0 k_B T
//   = (1 − k*) a / (1/(1 − φ)² − 2a) · ρ0 c².
// Defaults φ = 1/2, a = 1: P(n0) = ρ0 c²/2, and for all 0 < x < 2 both P > 0 and dP/dn > 0 (no van der Waals
// loop: the liquid is stable under any compression or expansion the flow can produce); the jump is
// (1 − k*) ρ0 c²/2.
#include <string>

namespace closurelab {

// (7.1) with the constants in model units; k_star is k_ij across phases.
struct VanDerWaalsEos {
  double kt = 0.0;  // k_B T
  double c1 = 0.0, c2 = 0.0;
  double k_star = 1.0;

  double pressure(double n, double k_ij) const { return n * kt / (1.0 - c1 * n) - k_ij * c2 * n * n; }
  double dpressure_dn(double n, double k_ij) const {
    const double d = 1.0 - c1 * n;
    return kt / (d * d) - 2.0 * k_ij * c2 * n;
  }
  double k_pair(int phase_i, int phase_j) const { return phase_i == phase_j ? 1.0 : k_star; }
  // The excess of P_i/n_i² (and of P_j/n_j²) in an unlike pair over its like-pair value: (1 − k*) c_2.
  double unlike_excess_over_n2() const { return (1.0 - k_star) * c2; }
  // (1 − k*) c_2 n0²: the interface pressure jump at the rest density.
  double interface_pressure_jump(double n0) const { return (1.0 - k_star) * c2 * n0 * n0; }

  // The largest admissible a for a given φ (exclusive): min(1/(1 − φ), 1/(2 (1 − φ)²)).
  static double a_max(double phi);
  // The parametrization above: rest number density n0, particle mass m, sound speed c at n0.
  // Throws ConfigError (at `path`) if φ, a or k* are outside 0 < φ < 1, 0 <= a < a_max(φ), 0 <= k* < 1.
  static VanDerWaalsEos from_liquid(double n0, double mass, double sound_speed, double phi, double a, double k_star,
                                    const std::string& path);
};

// The weakly compressible EOS of the single-phase scenes.
inline double weakly_compressible_pressure(double rho, double rho0, double sound_speed, double background) {
  return sound_speed * sound_speed * (rho - rho0) + background;
}

}  // namespace closurelab
