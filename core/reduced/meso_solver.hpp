#pragma once
// The reduced model (§5.2, §6, §7): the coarse balance (5.8), ρ̄ ∂_t v̄_x = ∂_y T_int,xy + F̄_x, for an
// x-invariant scene, stepped on a coarse mesh across the channel (spacing ≈ η') by the explicit scheme
// (5.11)–(5.14) with the time step (5.21)–(5.22) at Δ = mesh spacing. Each step closes the stress:
//   deconvolve v̄ (any registered Deconvolver, at the named discretization of §4.2) → the reconstruction,
//   sampled at the points the quadrature asks for (points in walls at rest) → T_int by the chosen
//   StressQuadrature (exact pair sum (2.13) or coarse (5.27)) → update.
// v̄ = 0 on the wall nodes (5.6)/(5.14), which are therefore not deconvolution data; F̄ is the averaged external force (2.14) of the lattice, divided by
// the averaged density (2.8). A conservative (staggered) variant evaluates T at mid-nodes and updates by
// the flux difference.
#include <Eigen/Core>
#include <array>
#include <string_view>
#include <utility>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/reconstruction.hpp"
#include "core/reduced/averaged_force_map.hpp"
#include "core/reduced/reduced_grid.hpp"
#include "core/base/enum_names.hpp"
#include "core/base/params.hpp"
#include "core/base/time_loop.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/reduced/integrator.hpp"

namespace closurelab {

// The solver's choices, named as the JSON names them (core/base/enum_names.hpp).
enum class MesoScheme { paper, staggered };                          // (5.11)–(5.14), or the conservative flux form
enum class MesoBalance { stress_divergence, force_density };
enum class WallNodeValue { imposed, reconstructed };
enum class BoundaryOracle { none, wall_nodes, wall_band };
template <>
struct EnumNames<MesoScheme> {
  static constexpr std::array<std::pair<MesoScheme, std::string_view>, 2> table{
      {{MesoScheme::paper, "paper"}, {MesoScheme::staggered, "staggered"}}};
};
template <>
struct EnumNames<MesoBalance> {
  static constexpr std::array<std::pair<MesoBalance, std::string_view>, 2> table{
      {{MesoBalance::stress_divergence, "stress_divergence"}, {MesoBalance::force_density, "force_density"}}};
};
template <>
struct EnumNames<WallNodeValue> {
  static constexpr std::array<std::pair<WallNodeValue, std::string_view>, 2> table{
      {{WallNodeValue::imposed, "imposed"}, {WallNodeValue::reconstructed, "reconstructed"}}};
};
template <>
struct EnumNames<BoundaryOracle> {
  static constexpr std::array<std::pair<BoundaryOracle, std::string_view>, 3> table{
      {{BoundaryOracle::none, "none"}, {BoundaryOracle::wall_nodes, "wall_nodes"}, {BoundaryOracle::wall_band, "wall_band"}}};
};

struct MesoSolverOptions : TimeLoopOptions {
  MesoSolverOptions() {
    max_time = 20.0;
    max_steps = 10000000;
  }
  double kappa = 0.25;                 // (5.21)–(5.22)
  double spacing_over_eta = 1.0;       // coarse mesh spacing Δ / η' (the paper: 1)
  MesoScheme scheme = MesoScheme::paper;
  Discretization discretization = Discretization::coarse_coarse;
  double noise_level = 0.0;            // δ handed to the deconvolver's parameter rule
  // Divergence: stop (numerical_issue) when max|v̄| exceeds this multiple of the scene's analytic peak; an
  // unstable closure otherwise runs on with (5.21) shrinking the step without bound.
  double divergence_factor = 1e3;
  // Called at each of the snapshot_times with the reported v̄.
  std::function<void(double time, const Eigen::VectorXd& v)> on_snapshot;
  // Wall particles are held at rest by constraint forces that (5.8) does not contain (DESIGN.md §6). When
  // true, their average F_c(y) = −Σ_walls f_i^int ψ(y − q_i), with f_i^int the pair forces (5.1) on wall
  // particle i under the reconstructed velocities, is added to the coarse balance. Costs one pair-force
  // sweep of the lattice per row next to a wall at setup; per step, O(nodes × those rows).
  bool wall_constraint_forces = false;
  // What the walled scenes report at the two wall-surface nodes: "imposed", the v̄ = 0 of (5.6); or
  // "reconstructed", the average (2.9) of the closure's reconstruction there (fluid rows at the reconstructed
  // velocity, wall particles at rest). An output only: the wall-surface nodes are not deconvolution data.
  WallNodeValue wall_node_value = WallNodeValue::imposed;
  // The right-hand side of the balance: "stress_divergence", the paper's finite difference of the stress
  // quadrature's T_int (plus the wall constraint forces when asked); or "force_density", the exact divergence
  // of (2.13) with the constraint forces included: Σ_{j fluid} ψ(x − q_j) f_j, the averaged pair force (5.1) on
  // the fluid particles under the reconstructed velocities, an affine map of the reconstruction on the fluid
  // rows probed once (positions stay on the lattice). With it, the wall-surface nodes are evolved (and are
  // deconvolution data) in the coarse–fine and fine–fine discretizations.
  MesoBalance balance = MesoBalance::stress_divergence;
  // The step itself is the Integrator's the solver is given (core/reduced/integrator.hpp; the solver section's
  // time_integration names it: "explicit", the paper's forward Euler, or "backward_euler", stable for the stiff
  // fluid–wall coupling of evolved wall-surface nodes, same steady state; or an ARKODE one, arkode_erk or
  // arkode_imex, with its parameters: the 1D model offers no stiff split, so arkode_imex steps it implicitly whole).
};

// Oracle substitution (the error budget): ingredients of the reduced model replaced by their exact
// counterparts taken from the direct SPH of the same scene. The quadrature oracle is the exact pair sum
// (2.13), a quadrature like any other; the two here are the closure and the boundary values.
struct MesoOracles {
  // Closure oracle: the reconstruction becomes R(v̄) + (V_d − R(v̄_d)), with R the closure, V_d the direct
  // SPH's particle velocity (x-mean per lattice row) and v̄_d its average at the coarse nodes: exact at the
  // direct solution, and as responsive to v̄ as the closure itself (a fixed V_d would leave no steady state).
  bool closure = false;
  // Boundary oracle: "none"; "wall_nodes": the two wall-surface nodes held at v̄_d instead of (5.6);
  // "wall_band": every node within 3η' of a wall surface held at v̄_d.
  BoundaryOracle boundary = BoundaryOracle::none;
  // Positions oracle (the sheared lattice): the force-density balance's map, ρ̄ and F̄ probed on these particles
  // (the direct run's final state, whose rows have slid against each other) instead of on the lattice; unset: the
  // lattice. Only with the force-density balance (ConfigError at /oracle/positions otherwise).
  std::optional<ParticleSystem> positions;
  Eigen::VectorXd averaged;             // v̄_d at the coarse nodes
  Eigen::VectorXd row_y, row_velocity;  // the fluid lattice rows (ascending y) and V_d there
};

// A reduced-model run's record, in one and two dimensions: the loop's outcome and what the closure cost.
// The parameters a deconvolver's rule chose over a run's solves (empty when its rule is fixed).
struct ParameterChoiceRecord {
  std::string rule, parameter_name;
  long solves = 0;
  double first = 0.0, last = 0.0, min = 0.0, max = 0.0;
  long noted_solves = 0;   // solves whose choice lay at the edge of the rule's scan (DeconvolutionStats::note)
  std::string first_note;  // the first one's note
  void add(const DeconvolutionStats& stats);  // ignores solves with rule fixed
  json to_json() const;  // "notes" {solves, first} when a choice lay at the edge of the scan
};

// Deconvolutions that reported a numerical issue (e.g. a solution that fits the data no better than x = 0): a run
// that goes on with them is not trustworthy, and the experiment kinds say so in the row's status.
struct DeconvolutionIssues {
  long solves = 0;
  std::string first;  // the first one's message
  void count(const DeconvolutionResult& r);
};

struct ClosureRunResult : TimeLoopResult {
  long deconvolution_matvecs = 0;
  double deconvolution_seconds = 0.0, quadrature_seconds = 0.0;
  QuadratureCost quadrature_cost;
  ParameterChoiceRecord parameter_choice;
  DeconvolutionIssues deconvolution_issues;
  json to_json() const;  // everything but the fields ("parameter_choice" when a rule chose)
};

struct MesoResult : ClosureRunResult {
  Eigen::VectorXd y, v;  // coarse nodes and v̄_x there
};

// The rules both reduced models (1D and 2D) step by: the time step (5.21)–(5.22),
// κ · min(ρ Δ²/μ_max, Δ/|v|_max) (the second only for a moving state); and the state check, false with the
// reason in `issue` when the state is not finite or its largest |v| exceeds divergence_factor × the analytic peak
// (an unstable closure otherwise runs on with (5.21) shrinking the step without bound).
double coarse_time_step(double kappa, double rho, double spacing, double max_viscosity, double max_speed);
bool coarse_state_ok(bool finite, double max_abs, double analytic_peak, double divergence_factor, std::string& issue);

// The solver section of a spec ("solver": {...}), each option declared once (an OptionTable,
// core/base/option_table.hpp, in meso_solver_schema.cpp): its schema, defaults from MesoSolverOptions{}
// (meso_options_from(resolved defaults) == MesoSolverOptions{}, tested), and the options read from a resolved
// section (the run-control parameters as core/base/time_loop.hpp declares them).
ParamSchema meso_solver_schema();
MesoSolverOptions meso_options_from(const json& resolved_solver);

// The solver's meshes for these options (core/reduced/reduced_grid.hpp).
ReducedGrid reduced_grid(const Scene& scene, const AveragingKernel& kernel, const MesoSolverOptions& options);
// What the solver's constructor checks before any work (the grid, the quadrature's fit), for validating a spec
// without building the strategies: ConfigError with the JSON path of the section at fault. The deconvolver is
// bound to its operator when the cell runs (a configuration that does not fit the operator fails that cell).
void check_meso_solver(const Scene& scene, const AveragingKernel& kernel, const StressQuadrature& quadrature,
                       const MesoSolverOptions& options);
// The run-control checks of a resolved solver section that need the scene and the coarse mesh, before anything
// runs: check_stepped_run (core/sph/sph_run.hpp) at the coarse spacing, every step at most (5.22)'s
// kappa·rho Δ²/mu_max (ConfigError at `path`/target_time or `path`/steady_window).
void check_meso_run(const Scene& scene, const AveragingKernel& kernel, const json& resolved_solver,
                    const MesoSolverOptions& options, const std::string& path);

class MesoSolver {
 public:
  // The kernel, deconvolver, quadrature and integrator must outlive the solver. Throws ConfigError when the scene
  // or options do not fit (no x-invariance, too few coarse nodes).
  MesoSolver(const Scene& scene, const AveragingKernel& kernel, Deconvolver& deconvolver, StressQuadrature& quadrature,
             Integrator& integrator, MesoSolverOptions options);

  MesoResult run();
  // v̄ on the coarse nodes, and the closure's reconstruction sampled at points (for diagnostics/tests).
  const Eigen::VectorXd& velocity() const { return v_; }
  const UniformMesh1D& coarse_mesh() const { return coarse_; }
  Eigen::Matrix2Xd sample_reconstruction(const std::vector<Vec2>& points);
  // The averaged wall constraint forces at the coarse nodes for the current v̄ (deconvolves first); zero
  // when the option is off.
  Eigen::VectorXd wall_constraint_force();
  // Sets v̄ (e.g. an initial state other than rest); held nodes (the wall nodes, (5.6)) keep their values.
  void set_velocity(const Eigen::VectorXd& v);
  // Switches oracles on (before run()); ConfigError when they do not fit the scene.
  void set_oracles(MesoOracles oracles);
  // v̄ as reported: the state, with the wall-surface nodes as options.wall_node_value says.
  Eigen::VectorXd reported_velocity();
  // One step of size dt; returns false on a numerical issue (message in `issue`).
  bool step(double dt, std::string& issue);
  // What the closure deconvolves at the current v̄ (the data vector of deconvolver.solve) and the operator it was
  // bound to: for choosing the closure's parameter once from a state (the two-pass rule, core/reduced/closure_rule.hpp).
  Eigen::VectorXd deconvolution_data() const;
  const ForwardOperator& forward_operator() const { return op_; }
  double time_step() const;

 private:
  // The rate the integrator advances (the current v̄ set from u), the held nodes with it.
  CoarseRate coarse_rate();
  // run() under an integrator that finds the steady state itself (newton): one call of it, no time loop
  // (meso_stepping.cpp).
  MesoResult steady_state();
  MesoResult finished(MesoResult res);  // the result's fields, costs and record from the solver's state
  bool deconvolve(std::string& issue);    // v̄ → reconstruction_
  bool close_stress(std::string& issue);  // deconvolve + quadrature → t_
  bool rate(Eigen::VectorXd& dvdt, std::string& issue);  // ∂_t v̄ at the current v̄
  void hold_nodes();                      // held nodes back to their values
  Eigen::VectorXd constraint_force();     // F_c at the coarse nodes for the current reconstruction

  const Scene& scene_;
  const AveragingKernel& kernel_;
  Deconvolver& deconvolver_;
  StressQuadrature& quadrature_;
  Integrator& integrator_;
  MesoSolverOptions opt_;
  UniformMesh1D coarse_, data_, fine_, stress_axis_;  // data_: the nodes whose v̄ is deconvolved
  ForwardOperator op_;
  bool periodic_ = false;
  Eigen::VectorXd v_, accel_force_, rho_bar_, t_, reconstruction_;
  // The wall constraint forces, and the force density of the exact balance, as affine maps of the
  // reconstruction on the fluid rows (core/reduced/averaged_force_map.hpp); empty when not used.
  AveragedForceMap constraint_map_, force_density_map_;
  bool walls_are_data_ = false;
  // Nodes whose value is imposed, not evolved: the wall nodes (5.6) at zero, or oracle values.
  std::vector<bool> held_;
  Eigen::VectorXd held_values_;
  MesoOracles oracles_;
  std::optional<Reconstruction> oracle_correction_;  // V_d − R(v̄_d) on the fluid rows
  long matvecs_ = 0;
  double deconv_seconds_ = 0.0, quad_seconds_ = 0.0;
  QuadratureCost quad_cost_;  // the quadrature's setup and the calls so far
  ParameterChoiceRecord choice_;
  DeconvolutionIssues deconvolution_issues_;
};

}  // namespace closurelab
