#pragma once
// The one time loop of every time-stepping model (the direct SPH, the reduced model): steps of the model's own
// size, shortened to land on snapshot times and on the target time; every `steady_window` steps a state check
// (a failing one is a numerical issue), the relative change of an observable over the window (steady state
// when below the tolerance, as §7 prescribes: 0.001 % over 1000 steps) and a progress line; it gives up at
// max_time or max_steps (no_convergence, with a message saying why).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/status.hpp"

namespace closurelab {

// The run-control parameters, declared once for both models (each model's struct derives from this one and
// sets its own max_time and max_steps defaults).
struct TimeLoopOptions {
  bool to_steady_state = true;  // else: run to target_time
  double target_time = 0.0;
  double steady_tolerance = 1e-5;  // max|o(t) − o(t − window)| / max|o(t)|, o the model's observable
  int steady_window = 1000;        // steps
  double max_time = 100.0;         // give up (no_convergence) at this model time, in both modes
  std::int64_t max_steps = 50000000;
  double progress_seconds = 10.0;
  std::function<void(const std::string&)> progress;  // may be empty
  std::vector<double> snapshot_times;                // ascending model times
};

// What a model offers the loop.
struct SteppedModel {
  std::string name;                                         // names the model in progress lines
  std::function<double()> time_step;                        // the model's full step
  std::function<bool(double dt, std::string& issue)> step;  // false: a numerical issue, said in `issue`
  std::function<Eigen::VectorXd()> observe;                 // the field whose change decides steady state
  std::function<bool(std::string& issue)> check_state;      // false: the state is not usable (non-finite, diverged)
  std::function<void(double time)> snapshot;                // at each snapshot time; may be empty
  std::function<std::string()> describe;                    // model facts for the progress line; may be empty
};

struct TimeLoopResult {
  Status status = Status::no_convergence;
  std::string message;  // why, when the status is no_convergence or numerical_issue
  std::int64_t steps = 0;
  double time = 0.0, dt = 0.0, wall_seconds = 0.0, last_relative_change = 0.0;
  double cpu_seconds = 0.0;  // the process's CPU time over the loop, every thread (repeated_timing.hpp)
  json to_json() const;
};

TimeLoopResult run_time_loop(const SteppedModel& model, const TimeLoopOptions& options);

// The parameters of TimeLoopOptions as a spec's solver section names them, with `defaults`' values:
// mode (steady | target_time), target_time, steady_tolerance, steady_window, max_time, max_steps.
ParamSchema time_loop_schema(const TimeLoopOptions& defaults);
// Reads those parameters from a resolved solver section into `options`.
void read_time_loop(const json& resolved, TimeLoopOptions& options);
// Cross-parameter checks of a resolved section at JSON path `path`: target_time <= max_time, and in steady mode a
// window that can mean steady (and check_steady_reach below, where the scene is known): the section's kappa bounds every model's step by
// kappa·ρh²/μ_max ((5.22), h the model's spacing), so a window of W steps spans at most W·kappa viscous times of
// the spacing; under one, no relaxation shows in the change and a run stops at any distance from steady state
// (kappa = 1e-6: `converged` at 99 % error). The tolerance must be at most kMaxSteadyTolerance.
void check_time_loop(const json& resolved, const std::string& path);

constexpr double kMaxSteadyTolerance = 1e-2;
constexpr double kMaxSteadyDistance = 1e-2;
// What a steady test can guarantee, scene known: with the slowest mode relaxing like e^{-t/τ}, a change below
// `tol` over a window of model time w leaves the state within tol/(1 − e^{−w/τ}) of steady (relative). With
// w <= W·kappa·ρh²/μ_max and τ >= ρL²/(π²μ_max) (the Rayleigh quotient of a channel of width L = `spacings`·h
// between walls), w/τ <= π²·W·kappa/spacings², so this returns a lower bound on that distance.
double steady_distance_bound(const json& resolved, double spacings);
// Refuses (ConfigError at `path`/steady_window) a steady section whose steady_distance_bound exceeds
// kMaxSteadyDistance: its `converged` could be far from steady state.
void check_steady_reach(const json& resolved, double spacings, const std::string& path);
// Refuses (ConfigError at `path`/target_time) a target_time section that cannot reach its target within max_steps
// when no step exceeds `max_dt` (a model's largest step): it needs at least target_time / max_dt steps, and the run
// could only give up.
void check_steps_reach_target(const json& resolved, double max_dt, const std::string& path);

}  // namespace closurelab
