#pragma once
// The transport-velocity formulation (TVF) of Adami, Hu & Adams, J. Comput. Phys. 241 (2013) 292–307, an option of
// the direct SPH engine (SphFormulation::transport_velocity; the default stays the standard weakly compressible
// SPH of (5.1), bit for bit). Written to mirror PySPH 1.0b1's TVFScheme (pysph/sph/scheme.py) equation by
// equation, so that the two engines can be compared particle by particle:
//
//   number density   n_a = Σ_b W_ab (self included), ρ_a = m_a n_a, V_a = 1/n_a
//                    (pysph/sph/wc/transport_velocity.py SummationDensity: its d_V is n_a, its d_rho is ρ_a)
//   state equation   p_a = c² (ρ_a − ρ0) + X, X the scene's EOS background pressure
//                    (StateEquation with p0 = ρ0 c², b = 1; PySPH's X = 0)
//   momentum (eq. 8) m_a dv_a/dt = Σ_b (V_a² + V_b²) [ −p̄_ab ∇_a W_ab                       MomentumEquationPressureGradient
//                                   + η_ab (x_ab · ∇_a W_ab) / (r_ab² + ε) v_ab               MomentumEquationViscosity
//                                   + ½ (A_a + A_b) · ∇_a W_ab ]  + m_a g                     MomentumEquationArtificialStress
//                    p̄_ab = (ρ_b p_a + ρ_a p_b) / (ρ_a + ρ_b) (eq. 7); η_a = ν ρ_a, η_ab = 2 η_a η_b / (η_a + η_b)
//                    (eq. 6; ν = μ/ρ0 of the particle's phase); ε = 0.01 h² (PySPH's EPS); the extra stress
//                    A_a = ρ_a v_a ⊗ (ṽ_a − v_a), (A · ∇W)_i = A_ij ∂_j W; x_ab = x_a − x_b, v_ab = v_a − v_b.
//   background       m_a (dṽ_a/dt − dv_a/dt) = −p_b Σ_b (V_a² + V_b²) ∇_a W_ab (eq. 13; the same equation's auhat),
//                    p_b = `transport_background_pressure_factor` ρ0 c² (PySPH's pb = pb_factor p0)
//   step             v += ½Δt a;  ṽ = v + ½Δt â;  x += Δt ṽ;  evaluate a, â at (x, v, ṽ);  v += ½Δt a
//                    (pysph/sph/integrator_step.py TransportVelocityStep stage1/stage2, eqs. 14–17, in
//                    pysph/sph/integrator.py PECIntegrator: the predictor uses the previous evaluation)
//
// Every term is antisymmetric in the pair (∇_a W_ab = −∇_b W_ba, the rest symmetric), so the engine evaluates each
// listed pair once and gives −f to b, as for (5.1); PySPH sums each particle's neighbours itself (the same sums in
// another order: round-off). The transport velocity ṽ is engine state, equal to v at the first evaluation (PySPH's
// taylor_green.py leaves uhat = 0 there, so that its first evaluation carries A = −ρ v ⊗ v: a peer run sets
// uhat = u at t = 0).
//
// Walls and solids (fixed particles): the generalized wall condition of Adami, Hu & Adams, J. Comput. Phys. 231
// (2012) 7057–7075, as PySPH's TVFScheme applies it to its solid arrays (pysph/sph/wc/transport_velocity.py):
//   SetWallVelocity      ṽ_w = Σ_f v_f W_wf / Σ_f W_wf (fluid neighbours f; 0 where Σ_f W_wf <= 1e-12), and the
//                        ghost velocity v_g = 2 v_w − ṽ_w, v_w the wall's prescribed velocity (eqs. 22–23)
//   SolidWallPressureBC  p_w = Σ_f (p_f + ρ_f (g − a_w) · (x_w − x_f)) W_wf / Σ_f W_wf (eq. 27; a_w = 0: walls are
//                        fixed), ρ_w = ρ0 ((p_w − X) / p0 + 1), p0 = ρ0 c² (eq. 28 with b = 1)
//   a wall's volume      V_w = ε'² (PySPH's examples set solid.V = 1/dx² and never update it)
//   fluid–wall pair      the pressure and background terms above with the wall's ρ_w, p_w, V_w; the viscous term
//                        with the ghost velocity v_g in v_ab (SolidWallNoSlipBC); no extra-stress term
//                        (MomentumEquationArtificialStress sums fluid neighbours only).
#include <array>
#include <string_view>
#include <utility>

#include "core/base/enum_names.hpp"

namespace closurelab {

enum class SphFormulation {
  standard,            // weakly compressible SPH with the pair force (5.1), the velocity-Verlet step
  transport_velocity,  // Adami, Hu & Adams (2013), as PySPH's TVFScheme (this file)
};

template <>
struct EnumNames<SphFormulation> {
  static constexpr std::array<std::pair<SphFormulation, std::string_view>, 2> table{
      {{SphFormulation::standard, "standard"}, {SphFormulation::transport_velocity, "transport_velocity"}}};
};

// The engine's options (the solver section's `formulation` and `transport_background_pressure_factor`,
// core/sph/sph_run.cpp).
struct SphEngineOptions {
  SphFormulation formulation = SphFormulation::standard;
  double transport_background_pressure_factor = 1.0;  // p_b / (ρ0 c²); transport_velocity only
};

// What the TVF pair pass reads of a particle: density, pressure, V² = 1/n², η = ν ρ, velocity, and the extra stress
// A = ρ v ⊗ (ṽ − v).
struct TvfParticle {
  double rho, p, vol2, eta, vx, vy, axx, axy, ayx, ayy;
};

// The particle's inputs at density n (mass m, pressure p, kinematic viscosity nu, velocity v, transport velocity
// vt), computed as PySPH does (Vi = 1/d_V, Vi2 = Vi*Vi; etai = nu*rho; Axx = rho*u*(uhat - u), ...).
inline TvfParticle tvf_particle(double n, double m, double p, double nu, double vx, double vy, double vtx, double vty) {
  const double rho = m * n, vol = 1.0 / n;
  return {rho,           p,
          vol * vol,     nu * rho,
          vx,            vy,
          rho * vx * (vtx - vx), rho * vx * (vty - vy),
          rho * vy * (vtx - vx), rho * vy * (vty - vy)};
}

// The TVF pair terms for pair (a, b) with F = w'(r)/r and q = x_a − x_b (so ∇_a W_ab = F q), ε = 0.01 h² and the
// background pressure pb: (fx, fy) = m_a × a's acceleration due to b (pressure, viscosity, extra stress), (bx, by) =
// m_a × the background pressure's part of a's transport acceleration. Each term is written in the order of its
// PySPH equation (named at each).
// A wall particle of the generalized wall condition carries its ρ_w, p_w, V_w² and, as its velocity, the ghost velocity
// v_g; with walls = true the extra-stress term is multiplied by stress_weight, the product of the two particles'
// weights (1 for a fluid particle, 0 for a wall particle: a fluid–wall pair has no such term, without a branch;
// multiplying by 1 changes no bit). The terms are antisymmetric to the bit: the pair taken as (b, a, −q) gives the
// exact negatives (sums and products commute, negation distributes exactly).
template <bool walls = false>
inline void tvf_pair_force(const TvfParticle& a, const TvfParticle& b, double F, double qx, double qy, double eps,
                           double pb, double& fx, double& fy, double& bx, double& by, double stress_weight = 1.0) {
  const double gx = F * qx, gy = F * qy;  // DWIJ
  const double vol = a.vol2 + b.vol2;     // Vi2 + Vj2
  // MomentumEquationPressureGradient: pij = (rhoj p_i + rhoi p_j) / (rhoj + rhoi); tmp = -pij (Vi2 + Vj2).
  const double pij = (b.rho * a.p + a.rho * b.p) / (b.rho + a.rho);
  double tmp = -pij * vol;
  fx = tmp * gx;
  fy = tmp * gy;
  // MomentumEquationViscosity: etaij = 2 etai etaj / (etai + etaj); Fij = DWIJ . XIJ; tmp (Vi2 + Vj2) etaij Fij/(R2IJ + EPS).
  // (PySPH adds this equation only for nu > 0; η_a + η_b = 0 then gives no term instead of 0/0.)
  const double eta_sum = a.eta + b.eta;
  if (eta_sum > 0.0) {
    const double etaij = 2.0 * (a.eta * b.eta) / eta_sum;
    const double fij = gx * qx + gy * qy, r2 = qx * qx + qy * qy;
    tmp = vol * etaij * fij / (r2 + eps);
    fx += tmp * (a.vx - b.vx);
    fy += tmp * (a.vy - b.vy);
  }
  // MomentumEquationArtificialStress: Ax = ½ ((Axxi + Axxj) DWIJ[0] + (Axyi + Axyj) DWIJ[1]), tmp (Vi2 + Vj2) Ax.
  {
    double sx = 0.5 * ((a.axx + b.axx) * gx + (a.axy + b.axy) * gy);
    double sy = 0.5 * ((a.ayx + b.ayx) * gx + (a.ayy + b.ayy) * gy);
    if constexpr (walls) {
      sx *= stress_weight;
      sy *= stress_weight;
    }
    fx += vol * sx;
    fy += vol * sy;
  }
  // MomentumEquationPressureGradient's background part (eq. 13): tmp = -pb (Vi2 + Vj2).
  tmp = -pb * vol;
  bx = tmp * gx;
  by = tmp * gy;
}

}  // namespace closurelab
