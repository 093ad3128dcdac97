#pragma once
// Driving the direct SPH model to a target time or to steady state (§7: the solution changes by less
// than 0.001 % over 1000 steps) by the shared time loop (core/base/time_loop.hpp).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/time_loop.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/transport_velocity.hpp"

namespace closurelab {

// How the direct SPH reaches its result (SphRunOptions::method).
enum class SphMethod {
  march,              // time steps of the engine (the time loop: to steady state or to a target time)
  linearised_steady,  // the steady state on the frozen lattice by one sparse solve (core/sph/linearised_steady.hpp)
};
template <>
struct EnumNames<SphMethod> {
  static constexpr std::array<std::pair<SphMethod, std::string_view>, 2> table{
      {{SphMethod::march, "march"}, {SphMethod::linearised_steady, "linearised_steady"}}};
};

struct SphRunOptions : TimeLoopOptions {
  SphMethod method = SphMethod::march;
  double kappa = 0.25;  // (5.21)–(5.22)
  SphEngineOptions engine;  // the formulation (standard, or transport velocity) and its background pressure
  // The field whose change decides steady state; default: the x-velocities of the moving particles.
  // Lattice particles sliding past each other carry a persistent ~1e-4 velocity ripple, so experiments
  // pass the averaged (mesoscale) velocity here, the quantity they compare.
  std::function<Eigen::VectorXd(const ParticleSystem&)> observable;
  // Called at each of the snapshot_times with the particles.
  std::function<void(double time, const ParticleSystem&)> on_snapshot;
  SphRunOptions() {
    max_time = 100.0;
    max_steps = 50000000;
  }
};

struct SphRunResult : TimeLoopResult {
  std::int64_t moving_particles = 0, active_particles = 0, total_particles = 0;
  std::int64_t pair_evaluations = 0, list_rebuilds = 0;
  json to_json() const;
  // The cost columns of a validation row: wall and averaging seconds, steps, dt, model time, particle-steps
  // (and per second), pair evaluations.
  json cost_json(double averaging_seconds) const;
  static SphRunResult from_json(const json& j);  // the inverse of to_json (a stored run's record)
};

// Under method linearised_steady: no step (steps 0, time 0), the particles' velocities the solve's, wall_seconds its
// assembly, factorisation and solve, last_relative_change its final relative residual; the observable is taken
// once, at the end (as a steady run's last observation).
SphRunResult run_direct_sph(const Scene& scene, ParticleSystem& particles, const SphRunOptions& options);

// The parameter schema of the direct solver as experiment specs name it ("solver": {...}); its defaults are
// SphRunOptions{}'s (one source), and sph_run_options_from(resolved defaults) == SphRunOptions{} (tested).
ParamSchema sph_solver_schema();
SphRunOptions sph_run_options_from(const json& resolved_solver);
// A solver section stored before `formulation`, `transport_background_pressure_factor` and `method` were added,
// with their defaults (the standard formulation it marched): ExperimentKind::upgraded_params of the kinds with a direct solver.
json upgraded_sph_solver_params(json solver);
// The direct model's largest step, kappa·min(dx/c, rho dx²/mu_max) (the particles at rest; it only shrinks as they
// move); under the transport-velocity formulation kappa·min(h/c, rho h²/(2 mu_max)) (SphEngine::time_step).
double direct_step_bound(const Scene& scene, double kappa, SphFormulation formulation = SphFormulation::standard);
// Refuses (ConfigError at `path`/target_time) a target_time run that cannot reach its target within max_steps
// (check_steps_reach_target at direct_step_bound). `path` is the solver section's JSON path.
void check_run_can_finish(const Scene& scene, const json& resolved_solver, const std::string& path);
// The scene's slowest relaxation as steady_distance_bound reads it: the width, in units of `spacing`, of a channel
// between walls whose slowest mode relaxes as slowly, rho W²/(pi² mu_max). A channel: its walls' distance; a
// cellular mode relaxing at 2 k² nu: W = pi / (sqrt 2 k); a single sine mode (kolmogorov) at q² nu: W = pi / q.
// 0 where the scene states none (a porous medium): no steady-reach check.
double steady_reach_spacings(const Scene& scene, double spacing);
// The checks of a time-stepped model's resolved solver section (the direct SPH, the reduced models) before anything
// runs, `spacing` its mesh spacing h and `max_dt` its largest step, which must be at most kappa·rho h²/mu_max: a
// target_time run can finish (check_steps_reach_target) and a run called steady is near steady state
// (check_steady_reach across steady_reach_spacings, where the scene states its relaxation).
void check_stepped_run(const Scene& scene, const json& resolved_solver, double spacing, double max_dt,
                       const std::string& path);
// check_stepped_run for the direct SPH: spacing dx, steps of at most direct_step_bound. Refused (ConfigError at
// `path`/formulation): the transport-velocity formulation on ghost-velocity walls (it has its own wall condition),
// and the standard one on a scene that needs_transport_velocity. Under method linearised_steady (ConfigError at
// `path`/method): mode steady, the standard formulation and a scene check_linearised_steady takes.
void check_direct_run(const Scene& scene, const json& resolved_solver, const std::string& path);

}  // namespace closurelab
