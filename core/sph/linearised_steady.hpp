#pragma once
// The direct SPH's steady state on its frozen lattice by one sparse solve (the like-for-like steady comparator of a
// steady reduced model: both solve for the steady state, neither marches). The standard formulation's pair forces
// (5.1) and the summation density's rate are linearised about the lattice at rest (uniform n0 = Σ_b w(r_b), the
// pressure P0 = P(n0)), the fixed particles at their prescribed velocity U (zero, or a lid's):
//   f_a = Σ_b μ_ab F_ab (V_a − V_b) / n0²  −  β Σ_b (δn_a + δn_b) F_ab q_ab,   β = dP/dn / n0² − 2 P0 / n0³,
//   ṅ_a = Σ_b F_ab q_ab · (V_a − V_b),       F = w'(r)/r, q_ab = q_a − q_b,
// as the 2D force-density model linearises them (core/reduced/force_density_2d.hpp), here on every particle instead
// of a reconstruction. The steady state f_a + m g(q_a) = 0, ṅ_a = 0 of the moving particles a is a saddle-point
// system in (V, δn): the pressure map is −β Dᵀ of the continuity map D, so
//   [ −K   β Dᵀ ] [ V  ]   [ m g + known ]
//   [ β D   0   ] [ δn ] = [ known       ],   −K the viscous map (symmetric positive definite: the solids hold it).
// The fixed particles keep their density n0 (δn = 0; no continuity row of theirs): their summation density on a
// frozen lattice would have to be steady too, which holds each fluid particle at the edge of a solid particle's
// support to no flow along their bond, enforced through a pair force that vanishes there (w' → 0 at the support),
// so the multiplier δn grows without bound (measured with their rows in: δn up to 37 n0 at n = 32, k 12 points below
// the marched direct SPH's at n = 48); held at n0, k is within 0.3 points of the marched value
// (results/cylinders/linearised_steady).
// Solved by CHOLMOD's simplicial LDLᵀ under METIS's nested dissection of the system with −δ I in the δn block
// (δ = 1e-10 of the Schur complement's scale (β F q)² / (μ F / n0²): quasi-definite, so factored without pivoting),
// then refined against the unregularised system until its residual is below 1e-12 of the right-hand side or stops
// falling.
// What it leaves out, against the marched direct SPH: the particles' displacement from their sites (frozen
// lattice), the convective terms (the linearisation about rest: Stokes flow), and the background pressure's force
// on a displaced lattice. It takes the scenes of the force-density model: one particle per lattice site, the
// standard formulation, zero-velocity or prescribed-velocity solids (no ghost-velocity walls), one phase's
// equation of state without the van der Waals unlike-pair term.
#include <Eigen/Core>
#include <string>

#include "core/sph/particles.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

struct LinearisedSteadyResult {
  long velocity_unknowns = 0, density_unknowns = 0, nonzeros = 0, factor_nonzeros = 0;  // the factor: nnz(L)
  double assemble_seconds = 0.0, factor_seconds = 0.0, solve_seconds = 0.0;
  int refinements = 0;             // refinement steps against the unregularised system
  double relative_residual = 0.0;  // ‖b − M x‖∞ / ‖b‖∞ of the unregularised system at the end
  bool converged = false;          // relative_residual ≤ 1e-10
  std::string message;
  Eigen::VectorXd density_deviation;  // δn of each particle (0 where it is no unknown)
  double seconds() const { return assemble_seconds + factor_seconds + solve_seconds; }
};

// ConfigError (at `path`, the scene section's JSON path) for a scene it does not take (above).
void check_linearised_steady(const Scene& scene, const std::string& path);
// The steady state on the scene's lattice `ps` (as make_particles() places it): the moving particles' velocities
// are set to V, the fixed ones keep theirs; positions are untouched.
LinearisedSteadyResult solve_linearised_steady(const Scene& scene, ParticleSystem& ps);

}  // namespace closurelab
