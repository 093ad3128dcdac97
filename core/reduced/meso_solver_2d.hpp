#pragma once
// The reduced model in two dimensions (beyond the paper): the averaged balance (2.11) in both components on a
// doubly periodic coarse mesh, for scenes without walls whose flow depends on x and y (the cellular flow), or in the
// walled cavity (below):
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
// Two sets of equations (solver.equations):
//   momentum       (the default) the linear model: the particles stay on their lattice (§5.2), so ρ̄ is the
//                  lattice's, the pressure the uniform P* (its stress has no divergence), and the convective stress
//                  is left out: in the cellular flow ρ v·∇v is a gradient balanced exactly by a pressure (DESIGN.md
//                  §5), so neither moves the velocity (at Re = 1e-3 the direct SPH agrees with Stokes to 0.05 %).
//   mass_momentum  the averaged balances (2.10)–(2.11) in full, conservative in (ρ̄, ρ̄v̄), for flows whose
//                  particles travel (Taylor–Green at Re = 100):
//                    ∂_t ρ̄ = −div(ρ̄v̄),   ∂_t(ρ̄v̄) = div(T_int − Φ − c_lat P(ρ̄) I) + ρ̄F̄,
//                  Φ = ρ̄v̄⊗v̄ − T_c the convective flux with T_c (2.12) of the closure's velocities V:
//                  Φ = ρ̄ [A(V⊗V) − v̄⊗A(V) − A(V)⊗v̄ + 2 v̄⊗v̄], A the averaging of the forward operator (so Φ = ρ̄ A(V⊗V)
//                  when the closure reproduces its data, A V = v̄); P the scene's equation of state at ρ̄ (its
//                  number density ρ̄/m), c_lat the lattice's pressure-stress factor (lattice_pressure_factor): the
//                  pressure part of (5.24) for ρ, P slowly varying, as the paper's (5.27) argues (positions on the
//                  lattice, so T_int from the quadrature carries the viscous stress and the constant P*). Each flux
//                  is interpolated from the cell centres to the faces (order divergence_order) and differenced there,
//                  so mass and momentum are conserved. Left out: the transport-velocity terms of a TVF reference
//                  (ṽ − v is a particle-scale correction, zero on average for a smooth density) and the particles'
//                  displacement from the lattice (the interaction stress is evaluated on the lattice).
//                  The time step adds the sound speed to the largest speed in (5.21); `transport` and
//                  `coarse_pressure` switch the two nonlinear parts off (both off: the momentum balance in
//                  conservative form, equal to `momentum` to round-off, tested).
//   incompressible the flow assumed incompressible, as the paper's §5.2 assumes it (positions intact, ρ̄ the
//                  lattice's): ∂_t v̄ = Π[div(T_int − Φ)/ρ̄ + F̄], Φ as above (`transport`), the pressure a Lagrange
//                  multiplier: Π the discrete Leray projection (core/continuum/periodic_projection_2d.hpp) for the
//                  model's own divergence (face interpolation then face difference, of divergence_order), so the
//                  discrete divergence of v̄ stays where set_velocity put it (projected there). No sound speed in
//                  the time step: (5.21)–(5.22) with the largest speed.
// In a walled rectangle (the lid-driven cavity; core/reduced/walled_box_2d.hpp), incompressible and coarse–fine only:
// the nodes are cell-centred over the fluid's square, the faces n + 1 per row with the outermost on the walls; the
// closure solves for the fluid particles' velocities on their lattice with the walls' known velocities as data; the
// rate is div(T_int − Q) + F_c, T_int from the quadrature on the faces (its fluid–wall bonds included), Q the fluid's
// own convective flux on the faces, F_c the walls' constraint forces (the fluid's averaged balance closes exactly:
// tests/numerical/test_meso_solver_2d_walls.cpp), projected for no flow through the walls.
// Integrators (solver.time_integration, core/reduced/integrator.hpp): each set offers its rate whole and split for an
// IMEX integrator (arkode_imex): the viscous part div T_int implicit, the rest (convective flux, coarse pressure, mass
// flux, body force) explicit; under incompressible each part projected. The step is (5.21)–(5.22) whichever runs.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <string_view>
#include <utility>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/enum_names.hpp"
#include "core/base/mesh.hpp"
#include "core/base/params.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/continuum/periodic_projection_2d.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

struct WalledBox2D;  // core/reduced/walled_box_2d.hpp

// solver.equations (above).
enum class CoarseEquations { momentum, mass_momentum, incompressible };

template <>
struct EnumNames<CoarseEquations> {
  static constexpr std::array<std::pair<CoarseEquations, std::string_view>, 3> table{
      {{CoarseEquations::momentum, "momentum"},
       {CoarseEquations::mass_momentum, "mass_momentum"},
       {CoarseEquations::incompressible, "incompressible"}}};
};

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
  CoarseEquations equations = CoarseEquations::momentum;
  bool transport = true;        // mass_momentum: the mass flux of (2.10) and the convective flux Φ of (2.11)-(2.12)
  bool coarse_pressure = true;  // mass_momentum: the pressure of the coarse density, −c_lat P(ρ̄) I
  // Called at each of the snapshot_times with v̄_x and v̄_y at the coarse nodes.
  std::function<void(double time, const Eigen::VectorXd& vx, const Eigen::VectorXd& vy)> on_snapshot;
};

struct MesoResult2D : ClosureRunResult {
  TensorMesh2D mesh;       // the coarse nodes
  Eigen::VectorXd vx, vy;  // v̄ there (flat j * nx + i)
};

// The pressure-stress factor of the scene's lattice: particles of number density n on the square lattice of spacing
// dx at the uniform pressure P carry the interaction stress (2.13) −c_lat P I, c_lat = −Σ_k F(r_k) x_k² / (dx² n²)
// (F = w'(r)/r of the SPH kernel, n = Σ_k w(r_k) the summation density, self included); 1 in the continuum limit.
double lattice_pressure_factor(const Scene& scene);
// The centre values of a periodic field interpolated to the faces of `axis` (face i: the left or lower face of
// cell i) at order 2 ((c_{i−1} + c_i)/2) or 4 ((−c_{i−2} + 9 c_{i−1} + 9 c_i − c_{i+1})/16).
Eigen::VectorXd to_faces(const TensorMesh2D& cells, const Eigen::VectorXd& at_centres, int axis, int order);
// σ(θ_m), θ_m = 2π m / n: the imaginary part of the symbol of face_difference ∘ to_faces along one axis of n cells of
// spacing h (order 2: sin θ / h; order 4: [(9 cos(θ/2) − cos(3θ/2))/8] (27 sin(θ/2) − sin(3θ/2)) / (12 h)), zero at
// the mean and the Nyquist mode: the divergence the incompressible equations' projection removes.
std::vector<double> divergence_symbol(int n, double h, int order);

// The solver section of a 2D spec, each option declared once (an OptionTable, core/base/option_table.hpp, in
// meso_solver_2d_geometry.cpp): schema (defaults from MesoSolver2DOptions{}) and reader.
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
// A walled rectangle (the lid-driven cavity) takes the incompressible equations, the coarse–fine closure and the
// dense projection's mesh size: ConfigError at /solver/equations, /closure/discretization or
// /solver/spacing_over_eta.
void check_walled_meso_2d(const TensorMesh2D& coarse, const MesoSolver2DOptions& options);
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
  // Sets v̄ (e.g. the average of an initial velocity; under incompressible, its projection on a doubly periodic box);
  // sizes must match the coarse mesh. A walled box takes it as given: the average of the initial particles, whose
  // walls' part (the lid's, near its corners) has a normal component on the wall faces; the rates are projected, so
  // the discrete divergence keeps its initial value.
  void set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy);
  // ∂_t v̄ at the current v̄ (both components), for diagnostics and tests.
  bool rate(Eigen::VectorXd& ax, Eigen::VectorXd& ay, std::string& issue);

  const TensorMesh2D& coarse_mesh() const { return coarse_; }
  const ForwardOperator& forward_operator() const { return op_; }
  const Eigen::VectorXd& vx() const { return vx_; }
  const Eigen::VectorXd& vy() const { return vy_; }
  const Eigen::VectorXd& density() const { return rho_bar_; }      // ρ̄ (fixed under `momentum`)
  const Eigen::VectorXd& averaged_force_x() const { return fx_; }  // F̄ = (2.14) / (2.8) at the nodes
  const Eigen::VectorXd& averaged_force_y() const { return fy_; }

 private:
  // The closure's velocities on the solution grid from v̄'s `component` (0: x, 1: y); in a walled box the data are
  // the fluid's part of the average (walled_box_2d.hpp).
  bool deconvolve(const Eigen::VectorXd& v, int component, Eigen::VectorXd& x, std::string& issue);
  // ∂ along `axis` at the centres of a field on that axis's faces (periodic or walled).
  Eigen::VectorXd face_diff(const Eigen::VectorXd& on_faces, int axis) const;
  // The terms a rate evaluation includes: all of them (`at`), or for an IMEX integrator (CoarseRate::stiff and
  // nonstiff) the viscous part div T_int (implicit) apart from the rest (convective flux, coarse pressure, mass
  // flux, body force; explicit). Under incompressible each part is projected.
  enum class RatePart { all, stiff, nonstiff };
  // The closure's velocities on the solution grid (when `closure`) and T_int on both face meshes (xx, yx on x-faces;
  // xy, yy on y-faces; when `stress`, which needs `closure`, else zero) for the current v̄.
  struct FaceStress {
    Eigen::VectorXd rx, ry, txx, tyx, txy, tyy;
  };
  bool face_stress(bool closure, bool stress, FaceStress& s, std::string& issue);
  // The closure's velocities on the solution grid, sampled anywhere (bilinear between its nodes).
  VelocitySampler closure_sampler(const Eigen::VectorXd& rx, const Eigen::VectorXd& ry) const;
  // The convective flux Φ at the centres (xx, xy, yy) from the closure's velocities in `t` and the current v̄, ρ̄;
  // and `t` less Φ interpolated to its faces.
  std::array<Eigen::VectorXd, 3> convective_flux(const FaceStress& t) const;
  void subtract_convective_flux(FaceStress& t) const;
  // Walled box, incompressible: the rate's terms the walls add (walled_box_2d.hpp), into the face stress `t`
  // (less the fluid's convective flux, when `convective`) and the nodes' forces (plus F_c, when `stress`).
  bool add_wall_terms(bool convective, bool stress, FaceStress& t, Eigen::VectorXd& ax, Eigen::VectorXd& ay,
                      std::string& issue);
  // The rate of v̄ under momentum (the public rate() is its `all`) and under incompressible.
  bool momentum_rate(RatePart part, Eigen::VectorXd& ax, Eigen::VectorXd& ay, std::string& issue);
  bool incompressible_rate(RatePart part, Eigen::VectorXd& ax, Eigen::VectorXd& ay, std::string& issue);
  // The rate of u = (ρ̄v̄_x, ρ̄v̄_y, ρ̄) under mass_momentum.
  bool conservative_rate(RatePart part, const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string& issue);

  const Scene& scene_;
  Deconvolver& deconvolver_;
  StressQuadrature &on_x_faces_, &on_y_faces_;
  Integrator& integrator_;
  MesoSolver2DOptions opt_;
  TensorMesh2D coarse_, fine_, solution_;
  ForwardOperator op_;
  Eigen::VectorXd vx_, vy_, rho_bar_, fx_, fy_;
  double lattice_pressure_factor_ = 1.0, particle_mass_ = 1.0;
  std::unique_ptr<PeriodicProjection2D> projection_;  // incompressible only
  std::shared_ptr<WalledBox2D> walls_;                // the cavity's walls; null: a doubly periodic box
  long matvecs_ = 0;
  double deconv_seconds_ = 0.0, quad_seconds_ = 0.0;
  QuadratureCost quad_cost_;  // both quadratures' setup and calls
  ParameterChoiceRecord choice_;
  DeconvolutionIssues deconvolution_issues_;
};

}  // namespace closurelab
