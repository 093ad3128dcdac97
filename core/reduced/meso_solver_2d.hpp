#pragma once
// The reduced model in two dimensions (beyond the paper): the averaged balance (2.11) in both components on a
// doubly periodic coarse mesh, for scenes without walls whose flow depends on x and y (the cellular flow):
//   ρ̄ ∂_t v̄_a = ∂_x T_ax + ∂_y T_ay + ρ̄ F̄_a,   a = x, y,   T_ab = Σ f_a d_b (2.13).
// Each step closes the stress as the 1D model does: deconvolve both components of v̄ with the Kronecker operator
// A_y ⊗ A_x at the named discretization (§4.2; any registered Deconvolver, bound once, two solves per step) →
// the reconstruction (bilinear between its nodes) → T_int by a StressQuadrature (exact (2.13) or coarse (5.27)
// on a 2D R-grid). Conservative staggered form: the nodes are cell-centred, ((i+½)Δ, (j+½)Δ); T_xx and T_yx are
// evaluated on the x-faces (iΔ, (j+½)Δ), T_xy and T_yy on the y-faces ((i+½)Δ, jΔ), so each node's update is
// a difference of face fluxes and the momentum of the box is conserved (second order, or a fourth-order
// staggered difference of the same face values: divergence_order). One quadrature instance per face mesh.
// Time step (5.21)–(5.22) with Δ the mesh spacing and |v̄| the largest speed.
//
// Left out because the scene does not need it (DESIGN.md §1): the particles stay on their lattice (§5.2), so
// the pressure is the uniform P* and its stress has no divergence; the convective stress (2.12) is left out as
// well: in the cellular flow ρ v·∇v is a gradient, balanced exactly by a pressure (DESIGN.md §5), so neither
// moves the velocity (at the scene's Re = 1e-3 the direct SPH agrees with the Stokes amplitude to 0.05 %).
#include <Eigen/Core>
#include <functional>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/base/params.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

struct MesoSolver2DOptions : TimeLoopOptions {
  MesoSolver2DOptions() {
    max_time = 20.0;
    max_steps = 10000000;
  }
  // (5.21)–(5.22): half the 1D default, as the explicit 2D diffusion limit is half the 1D one.
  double kappa = 0.125;
  double spacing_over_eta = 1.0;  // Δ / η'
  // The order of the face-flux difference: 2, (T_{i+½} − T_{i−½}) / Δ; or 4, the fourth-order staggered
  // [27 (T_{i+½} − T_{i−½}) − (T_{i+3/2} − T_{i−3/2})] / (24 Δ), still a difference of composite fluxes
  // (conservative) from the same face values. On a mode of wavenumber k the second order keeps
  // sin(kΔ/2)/(kΔ/2) of the derivative (0.64 % short at kΔ = 2π/16), the fourth order 1 − 1.2e-4. Measured on the
  // cellular flow at n = 96, coarse–fine CGLS: 0.81 % (order 2) and 0.24 % (order 4) from the averaged direct SPH.
  int divergence_order = 4;
  Discretization discretization = Discretization::coarse_coarse;
  double noise_level = 0.0;        // δ handed to the deconvolver's parameter rule
  double divergence_factor = 1e3;  // numerical_issue when max|v̄| exceeds this multiple of the analytic peak
  // Called at each of the snapshot_times with v̄_x and v̄_y at the coarse nodes.
  std::function<void(double time, const Eigen::VectorXd& vx, const Eigen::VectorXd& vy)> on_snapshot;
};

struct MesoResult2D : ClosureRunResult {
  TensorMesh2D mesh;        // the coarse nodes
  Eigen::VectorXd vx, vy;  // v̄ there (flat j * nx + i)
};

// The solver section of a 2D spec: schema (defaults from MesoSolver2DOptions{}) and reader.
ParamSchema meso_solver_2d_schema();
MesoSolver2DOptions meso_2d_options_from(const json& resolved_solver);

// The doubly periodic coarse mesh of spacing ≈ spacing_over_eta · η' (cell-centred); ConfigError at /scene (walls,
// or a box not periodic in both directions) or /solver/spacing_over_eta (fewer than 4 nodes along a side).
TensorMesh2D coarse_mesh_2d(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta);
// The two face meshes of the staggered form: x-faces (T_xx, T_yx) and y-faces (T_xy, T_yy).
TensorMesh2D x_faces_of(const TensorMesh2D& coarse);
TensorMesh2D y_faces_of(const TensorMesh2D& coarse);
// ∂_x (axis 0) or ∂_y (axis 1) at the cell centres of `cells` of a periodic field given on the faces of that axis
// (face i: the left or lower face of cell i), by the staggered difference of the given order (2 or 4; see
// MesoSolver2DOptions::divergence_order).
Eigen::VectorXd face_difference(const TensorMesh2D& cells, const Eigen::VectorXd& on_faces, int axis, int order);
// The structural checks before any work (mesh, each quadrature's fit on its face mesh), for validating a spec.
void check_meso_solver_2d(const Scene& scene, const AveragingKernel& kernel, const StressQuadrature& quadrature,
                          const MesoSolver2DOptions& options);
// check_stepped_run (core/sph/sph_run.hpp) at the coarse mesh's smaller spacing Δ, every step at most
// kappa·rho Δ²/mu_max: ConfigError at `path`/target_time or `path`/steady_window.
void check_meso_run_2d(const Scene& scene, const AveragingKernel& kernel, const json& resolved_solver,
                       const MesoSolver2DOptions& options, const std::string& path);

class MesoSolver2D {
 public:
  // The kernel, deconvolver, both quadratures (two instances of one configuration) and the integrator (explicit:
  // (5.21)–(5.22) bound the step for the forward Euler step) must outlive the solver.
  MesoSolver2D(const Scene& scene, const AveragingKernel& kernel, Deconvolver& deconvolver,
               StressQuadrature& on_x_faces, StressQuadrature& on_y_faces, Integrator& integrator,
               MesoSolver2DOptions options);

  MesoResult2D run();
  bool step(double dt, std::string& issue);  // false on a numerical issue (message in `issue`)
  double time_step() const;
  // Sets v̄ (e.g. the average of an initial velocity); sizes must match the coarse mesh.
  void set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy);
  // ∂_t v̄ at the current v̄ (both components), for diagnostics and tests.
  bool rate(Eigen::VectorXd& ax, Eigen::VectorXd& ay, std::string& issue);

  const TensorMesh2D& coarse_mesh() const { return coarse_; }
  const ForwardOperator& forward_operator() const { return op_; }
  const Eigen::VectorXd& vx() const { return vx_; }
  const Eigen::VectorXd& vy() const { return vy_; }
  const Eigen::VectorXd& averaged_force_x() const { return fx_; }  // F̄ = (2.14) / (2.8) at the nodes
  const Eigen::VectorXd& averaged_force_y() const { return fy_; }

 private:
  bool deconvolve(const Eigen::VectorXd& v, Eigen::VectorXd& x, std::string& issue);

  const Scene& scene_;
  Deconvolver& deconvolver_;
  StressQuadrature &on_x_faces_, &on_y_faces_;
  Integrator& integrator_;
  MesoSolver2DOptions opt_;
  TensorMesh2D coarse_, fine_, solution_;
  ForwardOperator op_;
  Eigen::VectorXd vx_, vy_, rho_bar_, fx_, fy_;
  long matvecs_ = 0;
  double deconv_seconds_ = 0.0, quad_seconds_ = 0.0;
  QuadratureCost quad_cost_;  // both quadratures' setup and calls
  ParameterChoiceRecord choice_;
  DeconvolutionIssues deconvolution_issues_;
};

}  // namespace closurelab
