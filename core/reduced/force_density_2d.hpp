#pragma once
// The linearised force-density reduced model in two dimensions, with solids (beyond the paper): the
// averaged balance of a scene periodic in x, and in y or bounded by walls in y, whose particles stay near their
// lattice sites (Stokes flow, Re ≪ 1), solids given by position (the scene's frozen particles: walls, or a lattice of
// cylinders; the walls are solids like any other), on a tensor coarse mesh of spacing Δ ≈ η' (one column for an
// x-invariant scene: a channel is the n_x = 1 case). The state is v̄ (both components) and n̄, the average of the particles' number-density
// deviation δn (the pressure's carrier: P = c²(m n − ρ0) + P_b):
//   ρ̄ ∂_t v̄ = Σ_{a fluid} ψ(x − q_a) (f_a + m g(q_a)),     ∂_t n̄ = Σ_a ψ(x − q_a) ṅ_a / Σ_a ψ(x − q_a),
// the exact averaged balance (2.11) of the fluid particles (the force density: the divergence of (2.13) plus the
// solids' constraint forces, as the 1D model's force_density balance) and the average of the summation density's
// rate. The pair forces (5.1) and ṅ_a are linearised about the lattice at rest (uniform n0, P0), with the solid
// particles at their known zero velocity:
//   f_a = Σ_b μ_ab F_ab (V_a − V_b) / n0²  −  β Σ_b (δn_a + δn_b) F_ab q_ab,   β = dP/dn / n0² − 2 P0 / n0³,
//   ṅ_a = Σ_b F_ab q_ab · (V_a − V_b),      F = w'(r)/r, q_ab = q_a − q_b.
// Left out unless asked (solver.convective_stress; DESIGN.md §1: a Stokes scene does not need it): the convective
// flux. With it, the momentum rate gains the exact averaged transport of the particles' momentum,
//   ρ̄ ∂_t v̄ ∋ Σ_{a fluid} m V_a (V_a · ∇_q ψ(x − q_a)) = −∇ · Σ_a m V_a V_a ψ(x − q_a)   (ρ̄ v̄v̄ − T_conv, (2.12)),
// with V_a the reconstructed particle velocities at the lattice sites: quadratic in the state, so the steady state
// is reached by Newton's method from the Stokes solution (the Jacobian exact: the closure is linear). The density's
// transport Σ δn_a V_a · ∇_q ψ stays out (δn V against n0 ∇·V: δn/n0 ≤ 4e-2 at the cylinder scene's Re ~ 1).
// The pair forces may instead be those of the transport-velocity formulation (solver.pair_forces: transport_velocity;
// core/sph/transport_velocity.hpp), for a reference computed under it, linearised about the same lattice at rest:
//   f_a = Σ_b (V_a² + V_b²) [η_ab F r²/(r² + ε) (V_a − V_b) − p̄_ab F q_ab],   V² = 1/n², ε = 0.01 h²,
// with p̄_ab's linear part ½(δp_a + δp_b), which for two fluid particles is the standard β term above. A solid
// particle w carries the generalized wall condition: the ghost velocity −Σ_f W_wf V_f / Σ_f W_wf, the pressure
// Σ_f (p_f + ρ_f g · (x_w − x_f)) W_wf / Σ_f W_wf and V_w² = ε'⁴ (its own δn does not enter the forces). The
// hydrostatic part and the rest pressure's force where V_w² ≠ 1/n0² are affine, added to the body force. The
// formulation's own extra stress ρ V (Ṽ − V) and its background pressure move the particles off the lattice and
// vanish on it: left out, as the particles' departure from their sites is.
// Always left out: the background pressure's force on the displaced lattice (−2P0/n0² δ(F q), which grows with the
// displacement, not with δn: 2P0/(c² ρ0) = 0.4 % of the pressure response at the cylinder scene's P0 = 0.002 ρ0 c²).
//
// Closure: the particle velocities V and density deviations δn are reconstructed from v̄ and n̄ by two registered
// Deconvolvers on a reconstruction mesh of spacing Δ / reconstruction_refinement, interpolated bilinearly to the
// particles; their forward operators are the averages (2.9) and Σψδn/Σψ of those particles: A_v = ρ̄⁻¹ Σ_fluid m ψ P_a
// (the solid particles enter ρ̄ at zero velocity: the known zeros of the solid are data of the deconvolution, not
// unknowns; the velocity's unknowns are the reconstruction nodes some fluid particle reads, the others are zero)
// and A_n = (Σψ)⁻¹ Σ_all ψ P_a. All the maps from the reconstruction to the coarse rates are affine and
// assembled once (dense, coarse nodes × reconstruction nodes), entries with ψ below window_cutoff · ψ(0) dropped.
// Steady state (solver.time_integration newton, the default): the closure must be linear in its data (a fixed
// parameter); one linear solve of the probed affine rate, bordered by the total density deviation, which the rate
// leaves free (and, with the convective flux, Newton's iteration from that Stokes solution).
// Marched (any stepping integrator of the family, core/reduced/integrator.hpp): the state z = (v̄_x, v̄_y, n̄) on the
// free nodes from rest, as the direct SPH starts, advanced by the rate above with the closure re-applied at every
// evaluation (so any registered deconvolver serves, cg included, under an integrator that does not probe the rate),
// by the shared time loop (core/base/time_loop.hpp) to a steady state or a target time. The loop's step is (5.21)–
// (5.22) on the coarse spacing with the sound speed in the signal speed (n̄ carries the pressure: the system is
// acoustic), κ · min(ρ0 Δ²/μ, Δ/(c + max|v̄|)); an ARKODE integrator takes its own internal steps within it. Its
// IMEX split: the linear maps of the pair forces (viscous, pressure, continuity) implicit, the body force and the
// convective flux explicit. (The paper's forward Euler diverges there: its stability region holds no part of the
// imaginary axis, where the acoustic modes lie; measured on the cylinder lattice, results/cylinders/reduced_tvf_marched.)
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <string_view>
#include <utility>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/enum_names.hpp"
#include "core/base/mesh.hpp"
#include "core/base/params.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/reduced/integrator.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/transport_velocity.hpp"

namespace closurelab {

// Where the reconstruction's nodes lie along a walled y (ForceDensity2DOptions::reconstruction_y_nodes): cell-centred
// across the whole box (a wall surface on a cell face), on the wall surfaces and evenly between, at the coarse rows
// refined, continued into the walls, or on the particle lattice's rows (the columns still the coarse ones refined).
enum class ReconstructionYNodes { cell_centred, on_wall_surfaces, lattice_rows };
template <>
struct EnumNames<ReconstructionYNodes> {
  static constexpr std::array<std::pair<ReconstructionYNodes, std::string_view>, 3> table{
      {{ReconstructionYNodes::cell_centred, "cell_centred"},
       {ReconstructionYNodes::on_wall_surfaces, "on_wall_surfaces"},
       {ReconstructionYNodes::lattice_rows, "lattice_rows"}}};
};

// What a held coarse node reports (ForceDensity2DOptions::held_node_value).
enum class HeldNodeValue { imposed, reconstructed };
template <>
struct EnumNames<HeldNodeValue> {
  static constexpr std::array<std::pair<HeldNodeValue, std::string_view>, 2> table{
      {{HeldNodeValue::imposed, "imposed"}, {HeldNodeValue::reconstructed, "reconstructed"}}};
};

// The run control (mode steady or target_time, ...; core/base/time_loop.hpp) applies when marched.
struct ForceDensity2DOptions : TimeLoopOptions {
  double spacing_over_eta = 1.0;      // Δ / η'
  int reconstruction_refinement = 2;  // the reconstruction mesh's spacing is Δ / this (1: the coarse mesh; 0: the lattice)
  // Along a walled y (refinement ≥ 1): where the reconstruction's nodes lie. The fluid particles next to a wall read
  // the wall's pair forces at their own velocity, so the interpolant's error there is amplified by 1/ε' against the
  // wall shear; with a node on the surface that error is O(ε' Δ_r |u''|), with the surface on a cell face O(Δ_r² |u''|);
  // on the lattice's rows every particle reads its own row (measured: the only choice whose error falls with n on
  // cylinder-channel, with the difference prior; results/walls_2d).
  ReconstructionYNodes reconstruction_y_nodes = ReconstructionYNodes::cell_centred;
  double window_cutoff = 1e-10;       // ψ below this fraction of ψ(0) is dropped from the assembled maps
  // Coarse nodes whose window's fluid mass fraction f = Σ_fluid m ψ / ρ̄ is below this are held: neither evolved nor
  // deconvolution data. Their v̄ is at most f times the largest fluid velocity in the window, and that fluid sits
  // at the surface, so the imposed zero is within f of the peak. Free nodes of small f are poorly determined by the
  // steady balance (their rows are weak): at 1e-3 the nodes inside the cylinder at a = 0.3 L, n = 192 read 1.9 % of
  // the peak against 0.38 % outside; from 1e-2 the error is flat to 3e-2 (results/cylinders/reduced).
  double hold_fraction = 1e-2;
  HeldNodeValue held_node_value = HeldNodeValue::imposed;
  double noise_level = 0.0;           // δ handed to the deconvolvers' parameter rules (a fixed one ignores it)
  // The convective flux (above): for a flow whose Reynolds number is not small; not for an x-invariant scene (its
  // flux has no divergence). Newton stops when its step is below newton_tolerance of the state (max norms).
  bool convective_stress = false;
  // Whose pair forces are linearised (above): the standard formulation's (5.1), the solids at zero velocity, or the
  // transport-velocity formulation's with the generalized wall condition on the solids.
  SphFormulation pair_forces = SphFormulation::standard;
  double newton_tolerance = 1e-10;
  int newton_max_iterations = 20;
  // Marched: the loop's step coefficient (above; an ARKODE integrator's error control works inside the step).
  double kappa = 0.25;
};

// The solver section, each option declared once (an OptionTable, core/base/option_table.hpp, in
// force_density_2d_schema.cpp): schema (defaults from ForceDensity2DOptions{}) and reader.
ParamSchema force_density_2d_schema();
ForceDensity2DOptions force_density_2d_options_from(const json& resolved_solver);

// The coarse mesh of spacing ≈ spacing_over_eta · η': along x one column for an x-invariant scene, else cell-centred;
// along y cell-centred when periodic, else (walls in y) the 1D model's nodes, on both wall surfaces and evenly between
// ((5.6), core/reduced/reduced_grid.hpp). ConfigError at /scene (a box not periodic in x, or neither periodic nor
// walled in y) or /solver/spacing_over_eta (fewer than 4 nodes along a resolved side). The reconstruction mesh:
// the coarse one refined (one column stays one), across the whole box in a walled y (ConfigError at
// /solver/reconstruction_refinement when it is finer than the lattice).
TensorMesh2D force_density_coarse_mesh(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta);
TensorMesh2D force_density_reconstruction_mesh(const Scene& scene, const TensorMesh2D& coarse, int refinement,
                                               ReconstructionYNodes y_nodes = ReconstructionYNodes::cell_centred);
// The checks before any work, for validating a spec: the meshes, the lattice's particles on their sites.
void check_force_density_2d(const Scene& scene, const AveragingKernel& kernel, const ForceDensity2DOptions& options);

struct ForceDensity2DResult : ClosureRunResult {
  TensorMesh2D mesh;                // the coarse nodes
  Eigen::VectorXd vx, vy, density;  // v̄ and n̄ there (flat j * nx + i)
  long free_nodes = 0;                // evolved (the others held)
  long reconstruction_nodes = 0;      // the reconstruction mesh's
  double superficial_velocity = 0.0;  // ⟨u_x⟩ over the whole cell from the reconstructed particle velocities
  double setup_seconds = 0.0;         // assembling the maps and the deconvolvers' setup
  double assembly_seconds = 0.0;      // of which assembling the maps
  double probe_seconds = 0.0;         // probing the closure on unit data
  long newton_iterations = 0;         // with the convective flux: Newton's steps from the Stokes solution
  double newton_seconds = 0.0;        // and their time (within the run's)
  double newton_last_step = 0.0;      // the last step's size relative to the state (max norms)
  long rate_evaluations = 0;          // marched: the rate's evaluations (the closure applied at each)
};

class ForceDensitySolver2D {
 public:
  // Both deconvolvers (two instances of one configuration) must outlive the solver; bound here to A_v and A_n.
  // `stepper` null: the steady state (newton); else the integrator that marches the state (held by reference).
  ForceDensitySolver2D(const Scene& scene, const AveragingKernel& kernel, Deconvolver& velocity, Deconvolver& density,
                       ForceDensity2DOptions options, Integrator* stepper = nullptr);

  ForceDensity2DResult run();
  // Marched: one step of dt by the integrator (false on a numerical issue, said in `issue`), and the loop's step.
  bool step(double dt, std::string& issue);
  double time_step() const;
  // The rates at the current state on the free nodes (both components of v̄, then n̄), for tests.
  bool rate(Eigen::VectorXd& ax, Eigen::VectorXd& ay, Eigen::VectorXd& an, std::string& issue);
  // The rates on every coarse node from reconstructions rx, ry (velocity) and rn (density deviation) on the
  // reconstruction mesh: the assembled affine maps, for tests.
  void rates_from_reconstruction(const Eigen::VectorXd& rx, const Eigen::VectorXd& ry, const Eigen::VectorXd& rn,
                                 Eigen::VectorXd& ax, Eigen::VectorXd& ay, Eigen::VectorXd& an) const;
  // The convective flux's rates on every coarse node (−∇·Σ m V V ψ / ρ̄, both components) from a velocity
  // reconstruction; zero without solver.convective_stress.
  void convective_rates(const Eigen::VectorXd& rx, const Eigen::VectorXd& ry, Eigen::VectorXd& qx,
                        Eigen::VectorXd& qy) const;
  // Sets the state from fields on every coarse node (the held nodes' values are ignored).
  void set_state(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy, const Eigen::VectorXd& density);

  const TensorMesh2D& coarse_mesh() const { return coarse_; }
  const TensorMesh2D& reconstruction_mesh() const { return recon_; }
  const ForwardOperator& velocity_operator() const { return op_v_; }
  const ForwardOperator& density_operator() const { return op_n_; }
  // Bilinear interpolation from the reconstruction mesh to every lattice particle (rows: particles as
  // Scene::make_particles orders them), for tests.
  Eigen::VectorXd interpolate_to_particles(const Eigen::VectorXd& on_reconstruction_mesh) const;
  const std::vector<int>& free_nodes() const { return free_; }
  // The state on the free nodes (what the two deconvolvers are handed): v̄_x, v̄_y and n̄.
  const Eigen::VectorXd& free_vx() const { return vx_; }
  const Eigen::VectorXd& free_density() const { return n_; }
  // The velocity operator's columns: the reconstruction nodes some fluid particle reads.
  const std::vector<int>& velocity_unknowns() const { return velocity_columns_; }
  // The body force's average Σ_fluid ψ m g / ρ̄ at every coarse node.
  const Eigen::VectorXd& averaged_body_force_x() const { return body_x_; }

 private:
  struct Interp {  // bilinear weights of one particle on the reconstruction mesh
    std::array<int, 4> node;
    std::array<double, 4> weight;
  };
  static Interp bilinear_weights(const TensorMesh2D& periodic_mesh, const Vec2& q);
  bool deconvolve(Deconvolver& d, const Eigen::VectorXd& data, Eigen::VectorXd& x, std::string& issue);
  // Every column of `data` at once (Deconvolver::solve_columns), the velocity's on every reconstruction node.
  bool deconvolve_columns(Deconvolver& d, const Eigen::MatrixXd& data, Eigen::MatrixXd& x, std::string& issue);
  bool steady_solve(std::string& issue);
  // The state (v̄_x, v̄_y, n̄ on the free nodes) marched by the time loop; its status in `res`.
  void march(ForceDensity2DResult& res);
  // Which part of the rate an evaluation returns (the IMEX split above).
  enum class RatePart { all, stiff, nonstiff };
  // The rate of the stacked state u = (v̄_x, v̄_y, n̄) on the free nodes: the state set from u, the closure applied.
  bool stacked_rate(RatePart part, const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string& issue);
  // The convective flux's maps (force_density_2d_convective.cpp): assembled in the constructor when asked, and
  // Newton's iteration on the bordered steady system `big` z = rhs plus the flux, from z (the Stokes solution);
  // xv, x0v: the velocity closure's response to unit data and to zero data.
  void assemble_convective(const Scene& scene, const AveragingKernel& kernel, const ParticleSystem& lattice,
                           const Eigen::VectorXd& rho_bar);
  bool newton_convective(const Eigen::MatrixXd& big, const Eigen::VectorXd& rhs, const Eigen::MatrixXd& xv,
                         const Eigen::VectorXd& x0v, bool minimum_norm, Eigen::VectorXd& z, std::string& issue);
  // Σ_a D(n, a) w_a P(a, ·): a convective map weighted by a per-particle field, carried to the reconstruction nodes.
  Eigen::MatrixXd to_reconstruction(const Eigen::SparseMatrix<double, Eigen::RowMajor>& d, const Eigen::VectorXd& w) const;
  double superficial_velocity(std::string& issue);
  Eigen::VectorXd on_free(const Eigen::VectorXd& full) const;  // the free nodes' entries of a coarse field
  // A state on the free nodes as reported on every node: held nodes by the average (`full`: every node's row of
  // the forward operator) of the reconstruction.
  Eigen::VectorXd reported(const Eigen::VectorXd& state, Deconvolver& d,
                           const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& full,
                           std::string& issue);

  const Scene& scene_;
  Deconvolver &velocity_, &density_;
  ForceDensity2DOptions opt_;
  Integrator* stepper_ = nullptr;
  TensorMesh2D coarse_, recon_;
  ForwardOperator op_v_, op_n_;
  std::vector<Interp> interp_;
  std::vector<int> free_;                 // the evolved coarse nodes (the state's entries)
  std::vector<int> velocity_columns_;     // the reconstruction nodes some fluid particle reads (the velocity's unknowns)
  std::vector<std::uint8_t> fixed_;
  // The maps are row-major as assembled (a block row is contiguous there); the products with them are the same
  // either way.
  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajorMatrix full_v_, full_n_;        // A_v and A_n on every coarse node (the operators: free rows only)
  // Rates from the reconstruction (coarse nodes × reconstruction nodes), divided by ρ̄ for the momentum:
  // viscous (both components), pressure (x and y from δn), continuity (from V_x and V_y).
  RowMajorMatrix viscous_, pressure_x_, pressure_y_, continuity_x_, continuity_y_;
  Eigen::VectorXd body_x_, body_y_;   // Σ_fluid ψ m g / ρ̄
  Eigen::VectorXd mass_weight_;       // ρ̄ Δ² / (ρ0 L²): ⟨u⟩ = Σ mass_weight v̄ (the cell's momentum)
  Eigen::VectorXd vx_, vy_, n_;
  double fluid_area_per_particle_ = 0.0;
  long matvecs_ = 0;
  double deconv_seconds_ = 0.0, setup_seconds_ = 0.0, assembly_seconds_ = 0.0, probe_seconds_ = 0.0;
  DeconvolutionIssues deconvolution_issues_;
  // The convective flux: D_b(n, k) = m ∂_{q_b} ψ(x_n − q_a) / ρ̄_n over the fluid particles a = fluid_[k], and their
  // bilinear interpolation from the reconstruction mesh (rows: fluid particles).
  std::vector<int> fluid_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> conv_dx_, conv_dy_, fluid_interp_;
  // The rates' evaluation on the reconstruction's node pairs (force_density_2d_convective.cpp): T_b = D_b S over the
  // pairs {j, l} (j ≤ l) of nodes that share a cell; its cost does not grow with the particles.
  std::vector<std::array<int, 2>> pairs_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> pairs_x_, pairs_y_;
  long newton_iterations_ = 0;
  double newton_seconds_ = 0.0, newton_last_step_ = 0.0;
  long rate_evaluations_ = 0;  // marched: the closure applied this many times (three deconvolutions each)
};

// The closure must be linear in its data when the steady system is probed (`steady`: time_integration newton): not
// cg/cgls (ConfigError at `path`/closure/deconvolver); a parameter rule is served by the two-pass rule
// (core/reduced/closure_rule.hpp; each deconvolver's parameter chosen once from the steady state reached at its
// configured fixed parameter). Marched, the integrator's own needs are checked (check_implicit_closure).
void check_force_density_closure(const json& resolved_deconvolver, const std::string& path, bool steady = true);

}  // namespace closurelab
