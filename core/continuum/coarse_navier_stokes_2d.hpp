#pragma once
// The coarse continuum baseline ("what a user would pick instead"): the incompressible Navier–Stokes
// equations
//   ρ (∂_t v + ∇·(v ⊗ v)) = −∇p + μ Δv + ρ F,   ∇·v = 0,
// on a doubly periodic cell-centred mesh — the same TensorMesh2D the 2D reduced model steps on (coarse_mesh_2d,
// core/reduced/meso_solver_2d.hpp) — by a textbook second-order projection method on a collocated grid:
//  - space: every unknown (v_x, v_y, p) at the nodes; the convective flux divergence ∇·(v ⊗ v) by central
//    differences (f_{i+1} − f_{i−1}) / 2h of the products (conservative: the box's momentum changes only by the
//    force), the Laplacian by the 5-point stencil, divergence and gradient of the projection by the same central
//    differences. Second order: on a Fourier mode of wavenumber k the 5-point Laplacian's eigenvalue is
//    −Σ_a (4/h_a²) sin²(k_a h_a/2) = −|k|² (1 − O((kh)²/12)).
//  - time: Adams–Bashforth 2 (variable-step coefficients; the first step forward Euler) for the convective,
//    viscous and force terms together, then the exact discrete projection v ← v* − Δt G φ with D·G φ = D·v*/Δt,
//    solved in Fourier space (2D FFT by Eigen's unsupported FFT module, no new dependency): per mode, with
//    d = (sin θ_x / h_x, sin θ_y / h_y), v̂ ← v̂* − d (d·v̂*)/|d|². The central divergence of the result vanishes to
//    round-off. On a periodic box the projection commutes with the Laplacian, so nothing is lost by projecting
//    after the viscous update (no splitting error, no pressure boundary condition). Second order in time.
//  - step: Δt = min(cfl · h_min / max|v|, viscous_number · h_min² / ν) — the advective (CFL) limit and the
//    explicit diffusion limit (AB2 is stable on the negative real axis down to Δt λ = −1, and the 5-point
//    Laplacian's largest |λ| is ν (4/h_x² + 4/h_y²) ≤ 8ν/h_min², so viscous_number ≤ 1/8).
// Known property of the collocated grid: the modes at the Nyquist wavenumber (θ = π along an axis) have d = 0 along
// that axis, so the pressure does not see them (odd–even decoupling). The scenes here are single low modes whose
// convective term lives at twice their wavenumber (the Nyquist mode only at 4 nodes per wavelength), so nothing
// feeds them.
// Exact discrete properties (tests/numerical/test_coarse_navier_stokes_2d.cpp): the sampled Taylor–Green field is
// discretely divergence-free, its central convective term is a discrete gradient (removed by the projection to
// round-off), so the scheme keeps its shape and its amplitude follows AB2 applied to ν λ_h, λ_h the 5-point
// eigenvalue; the Kolmogorov flow F = F0 sin(ky) x̂ has no convective term and settles at F0 / (ν |λ_h|).
#include <Eigen/Core>
#include <memory>
#include <string>

#include "core/continuum/continuum_navier_stokes_2d.hpp"

namespace closurelab {

struct Scene;
class AveragingKernel;
class PeriodicProjection2D;

class CoarseNavierStokes2D : public ContinuumNavierStokes2D {
 public:
  // mesh: doubly periodic (both axes periodic, period = count · spacing); density ρ > 0, dynamic viscosity μ > 0;
  // force: the body force per unit mass at the nodes (flat j · nx + i; empty vectors: none). std::invalid_argument
  // on a mesh that is not doubly periodic, fewer than 4 nodes along a side, or sizes that do not match.
  CoarseNavierStokes2D(TensorMesh2D mesh, double density, double viscosity, Eigen::VectorXd force_x,
                       Eigen::VectorXd force_y, CoarseNavierStokes2DOptions options = {});
  ~CoarseNavierStokes2D();
  CoarseNavierStokes2D(const CoarseNavierStokes2D&) = delete;
  CoarseNavierStokes2D& operator=(const CoarseNavierStokes2D&) = delete;

  // Sets the velocity at the nodes (time 0, the AB2 history cleared) and projects it onto the discretely
  // divergence-free fields (a user's initial projection); returns the max-node magnitude of what the projection
  // removed. The caller picks the coarse data (the experiment kind passes the averaged particle velocity, as the
  // reduced model starts from).
  double set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) override;
  // One AB2 step of length dt followed by the projection. False (and the state unchanged) if the result is not
  // finite.
  bool step(double dt) override;
  double time_step() const override;  // the CFL and viscous limits at the current velocity
  std::string method() const override { return "collocated central differences, AB2, exact FFT projection"; }

  const TensorMesh2D& mesh() const override { return mesh_; }
  const Eigen::VectorXd& vx() const override { return vx_; }
  const Eigen::VectorXd& vy() const override { return vy_; }
  // The pressure of the last projection, ρ φ (zero mean), first order in time; zero before the first step.
  const Eigen::VectorXd& pressure() const { return p_; }
  // The central-difference divergence of the current velocity at the nodes.
  Eigen::VectorXd divergence() const override;
  // Bilinear interpolation of the node values, periodic in both directions.
  Eigen::Vector2d velocity_at(double x, double y) const override;
  // ∂_t v of the semi-discrete equations before the projection: −∇·(v⊗v) + ν Δv + F (for tests and diagnostics).
  void unprojected_rate(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy, Eigen::VectorXd& rx,
                        Eigen::VectorXd& ry) const;
  // The 5-point Laplacian's eigenvalue at the wavevector (kx, ky) (radians per unit length): −Σ (4/h²) sin²(kh/2).
  double laplacian_eigenvalue(double kx, double ky) const;

 private:
  void project(Eigen::VectorXd& vx, Eigen::VectorXd& vy, double dt);

  TensorMesh2D mesh_;
  double rho_, nu_;
  Eigen::VectorXd fx_, fy_;
  CoarseNavierStokes2DOptions opt_;
  std::unique_ptr<PeriodicProjection2D> projection_;
  Eigen::VectorXd vx_, vy_, p_, rx_prev_, ry_prev_;
  double dt_prev_ = 0.0;  // 0: no history (the next step is forward Euler)
};

// The scene's body force per unit mass sampled at the nodes (body_force, else force_x(y) along x; zero if neither).
void sampled_body_force(const Scene& scene, const TensorMesh2D& mesh, Eigen::VectorXd& fx, Eigen::VectorXd& fy);
// The averaged body force F̄ = (2.14) / (2.8) at the nodes: the velocity average (2.9) of the lattice's particles
// carrying F(q) as their velocity, as the 2D reduced model forms it (MesoSolver2D::averaged_force_x).
// With `density`, also ρ̄ (2.8) of the same particles.
void averaged_body_force(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh,
                         Eigen::VectorXd& fx, Eigen::VectorXd& fy, Eigen::VectorXd* density = nullptr);
// The baseline for a scene on a given mesh: ρ0, the one phase's viscosity and the body force, averaged with
// `average_force` where given (the coarse data the reduced model is driven by), else sampled at the nodes.
// std::invalid_argument for a scene the baseline cannot serve (walls, solids, several phases, not doubly periodic).
std::unique_ptr<CoarseNavierStokes2D> coarse_navier_stokes_for(const Scene& scene, const TensorMesh2D& mesh,
                                                               CoarseNavierStokes2DOptions options = {},
                                                               const AveragingKernel* average_force = nullptr);

}  // namespace closurelab
