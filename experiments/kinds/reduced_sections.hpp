#pragma once
// The spec sections that the reduced-model kinds share (reduced_model in 1D, reduced_model_2d): the closure,
// the direct SPH reference, the transient and the timing.
#include <functional>
#include <string>

#include "core/base/option_table.hpp"
#include "core/base/params.hpp"
#include "core/base/repeated_timing.hpp"
#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

// "closure", declared once for the options struct `O` of a stepped reduced model (MesoSolverOptions,
// MesoSolver2DOptions) that holds what it reads: the registered deconvolver with its parameters (an entry the kind
// creates from the registry), the discretization of R_η (§4.2) and the noise level δ handed to a parameter rule.
template <class O>
const OptionTable<O>& closure_section() {
  static const OptionTable<O> table =
      OptionTable<O>("/closure")
          .unbound(object_param("deconvolver", json{{"name", "landweber"}, {"order", 0}},
                                "registered deconvolver and its parameters"))
          .choice("discretization", &O::discretization, "discretization of R_eta (par. 4.2)")
          .number("noise_level", &O::noise_level, "delta handed to the deconvolver's parameter rule", 0.0);
  return table;
}
// "reference": whether to run the direct SPH of the same scene, its solver section, the observe-mesh spacing.
ParamSchema reference_schema();
// A transient section's snapshot times (`times`, an array at JSON path `path`): finite, positive, ascending;
// ConfigError at the first that is not.
void check_snapshot_times(const json& times, const std::string& path);

// "transient", the reduced models' one vocabulary: snapshot times `t_over_tau`, t / τ with τ the scene's time
// scale (Scene::time_scale()). The column model's earlier name `t_star` (t v_max / L, which is t / τ for its
// scenes) is read as t_over_tau; rows stored under it still match their specs (upgraded_reduced_params).
ParamSchema transient_schema();
// The key of `cell`'s transient section that holds its times as the cell wrote it ("t_star" or "t_over_tau"), for
// error paths.
std::string transient_times_key(const json& cell);
// The resolved transient section of `cell` (at JSON path `path`): {"t_over_tau": [...]}, the times checked; both
// names at once is a ConfigError.
json resolve_transient(const json& cell, const std::string& path);
// The snapshot model times t = (t / τ) τ of a resolved transient section.
std::vector<double> transient_times(const json& transient, const Scene& scene);
// What the reduced kinds' upgraded_params add to ExperimentKind::upgraded_params (the scene's and the strategies'
// upgrades, which they apply first): transient.t_star renamed t_over_tau; timing.min_seconds, added since, set to
// 0, as those rows were timed; the reference's direct solver its formulation (upgraded_sph_solver_params); an
// arkode_imex time_integration its linear_solver (gmres, as they ran).
json upgraded_reduced_params(json params);

// A deconvolver that needs a square operator (the Landweber series without a lift, Tikhonov's paper form) with a
// discretization whose operator is `rows` x `cols`, not square (coarse_fine: coarse data, fine unknowns): a
// ConfigError at `path`/closure/discretization at validation (it failed only at run time, "got 11x20").
void check_operator_shape(const json& closure, long rows, long cols, const std::string& path);

// TSVD by a truncation index k (`resolved_deconvolver`) on an operator of at most `rows` x `cols` (`shape` names
// them, e.g. "coarse nodes x reconstruction nodes"): a k above min(rows, cols), the most singular values it can
// have, is a ConfigError at `path`/closure/deconvolver/k at validation (it failed only when the cell ran).
// `under_rule`: the deconvolver has a rule and runs at k as pass 1 of the two-pass rule (said in the message).
void check_truncation_rank(const json& resolved_deconvolver, long rows, long cols, const std::string& shape,
                           bool under_rule, const std::string& path);

// The zero-end first difference ends its links at a 1D column's walls (strategies/deconvolution/
// difference_regularizers.cpp); on the 2D stepped model's Kronecker operator it is a ConfigError at
// `path`/closure/deconvolver/regularizer at validation (setup refused it only when the cell ran, after any direct SPH).
void check_prior_on_2d_operator(const json& resolved_deconvolver, const std::string& path);

// "timing": how the reduced run is repeated (core/base/repeated_timing.hpp).
ParamSchema reduced_timing_schema();

// One reduced run's two timed parts: building the solver (operators, factorizations, quadrature tables, the
// strategies' setup) and its time loop.
struct ReducedRunSeconds {
  double setup = 0.0, loop = 0.0;
};
// The reduced run repeated under `policy`: the statistics of the whole run (setup + loop), and the fastest
// setup and loop seen; `cpu`, the statistics of the same runs' process CPU time (process_cpu_seconds).
struct RepeatedReducedRuns {
  TimingStats total, cpu;
  double setup_min = 0.0, loop_min = 0.0;
};
RepeatedReducedRuns repeat_reduced_run(const std::function<ReducedRunSeconds()>& run_once, const TimingPolicy& policy);

// Writes the timing into a row's cost: setup_seconds and wall_seconds (the fastest setup and loop),
// reduced_timing (the statistics of setup + loop); with the direct run's record (`direct_run`, its
// "wall_seconds" and the store's "computed_by"): direct_sph_wall_seconds, speed_up (the direct time over the
// fastest reduced run), speed_up_at_median, and direct_sph_timing (the commit, host and date that timed the
// direct run and whether they are this run's). The same in CPU time (core-seconds, which a loaded machine's
// preemption does not inflate): reduced_timing.cpu, direct_sph_cpu_seconds and speed_up_cpu (the direct run's CPU
// time over the reduced runs' least), null with speed_up_cpu_note where the direct record has no CPU time (a store
// entry from before it was recorded).
void add_reduced_timing(json& cost, const RepeatedReducedRuns& runs, const json* direct_run);

// The reduced kinds' last step: the repeated timing into `cost` (add_reduced_timing, with the direct run's record
// `direct_run`), repeats_identical and the peak memory; `errors` and `cost` into the row; then the row's status the
// worst of its parts (propagate_worst_status).
void finish_reduced_row(json& row, json errors, json cost, const RepeatedReducedRuns& timing, bool repeats_identical,
                        const DeconvolutionIssues& deconvolution_issues, const json* direct_run);

// A reduced row's status, the worst of its parts: the reduced run's own (`status`, already in the row), then
// numerical issues of the closure's deconvolutions (any: numerical_issue), then the direct
// reference's (its record's "status": a reference that did not reach its steady state or target time makes the
// errors against it measure another flow). Sets row["status"] and, when it changed, row["message"].
void propagate_worst_status(json& row, const DeconvolutionIssues& deconvolution_issues, const json* direct_run);

// A parameter rule's choice at the edge of its scan (DeconvolutionStats::note), in the reduced run's record
// (reduced_model.parameter_choice.notes, reduced_model.two_pass_rule's rule_note) as row["note"]; the status stays.
void add_rule_notes(json& row);

}  // namespace closurelab
