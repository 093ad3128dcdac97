#pragma once
// Driving the direct SPH model to a target time or to steady state (§7: the solution changes by less
// than 0.001 % over 1000 steps), with progress reports and a non-finite check.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

struct SphRunOptions {
  double kappa = 0.25;            // (5.21)–(5.22)
  bool to_steady_state = true;    // else: run to target_time
  double target_time = 0.0;
  double steady_tolerance = 1e-5;  // max|v(t) − v(t − window)| / max|v(t)|
  int steady_window = 1000;       // steps
  double max_time = 100.0;        // give up (status no_convergence) after this model time
  std::int64_t max_steps = 50000000;
  double progress_seconds = 10.0;
  std::function<void(const std::string&)> progress;  // may be empty
  // The field whose change decides steady state; default: the x-velocities of the moving particles.
  // Lattice particles sliding past each other carry a persistent ~1e-4 velocity ripple, so experiments
  // pass the averaged (mesoscale) velocity here, the quantity they compare.
  std::function<Eigen::VectorXd(const ParticleSystem&)> observable;
  // Snapshots (ascending model times): the run lands a step on each and calls on_snapshot(time, particles).
  std::vector<double> snapshot_times;
  std::function<void(double time, const ParticleSystem&)> on_snapshot;
};

struct SphRunResult {
  std::string status;  // "converged" (steady state reached), "target_time", "no_convergence", "numerical_issue"
  std::int64_t steps = 0;
  double time = 0.0, dt = 0.0, wall_seconds = 0.0, last_relative_change = 0.0;
  std::int64_t moving_particles = 0, active_particles = 0, total_particles = 0;
  std::int64_t pair_evaluations = 0, list_rebuilds = 0;
  std::string message;  // why, when status is no_convergence or numerical_issue
  json to_json() const;
  static SphRunResult from_json(const json& j);  // the inverse of to_json (a stored run's record)
};

SphRunResult run_direct_sph(const Scene& scene, ParticleSystem& particles, const SphRunOptions& options);

// The parameter schema of the direct solver as experiment specs name it ("solver": {...}); its defaults are
// SphRunOptions{}'s (one source), and sph_run_options_from(resolved defaults) == SphRunOptions{} (tested).
ParamSchema sph_solver_schema();
SphRunOptions sph_run_options_from(const json& resolved_solver);
// Cross-parameter checks of a resolved solver section (`path` is its JSON path): target_time <= max_time.
void check_sph_solver(const json& resolved_solver, const std::string& path);

}  // namespace closurelab
