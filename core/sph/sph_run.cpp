#include "core/sph/sph_run.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "core/base/run_progress.hpp"
#include "core/base/snapshot_schedule.hpp"
#include "core/sph/sph_engine.hpp"

namespace closurelab {

json SphRunResult::to_json() const {
  json j = {{"status", status},
          {"steps", steps},
          {"time", time},
          {"dt", dt},
          {"wall_seconds", wall_seconds},
          {"last_relative_change", last_relative_change},
          {"moving_particles", moving_particles},
          {"active_particles", active_particles},
          {"total_particles", total_particles},
          {"particle_steps", static_cast<double>(moving_particles) * static_cast<double>(steps)},
          {"pair_evaluations", pair_evaluations},
          {"list_rebuilds", list_rebuilds}};
  if (!message.empty()) j["message"] = message;
  return j;
}

SphRunResult SphRunResult::from_json(const json& j) {
  SphRunResult r;
  r.status = j.at("status").get<std::string>();
  r.steps = j.at("steps").get<std::int64_t>();
  r.time = j.at("time").get<double>();
  r.dt = j.at("dt").get<double>();
  r.wall_seconds = j.at("wall_seconds").get<double>();
  r.last_relative_change = j.at("last_relative_change").get<double>();
  r.moving_particles = j.at("moving_particles").get<std::int64_t>();
  r.active_particles = j.at("active_particles").get<std::int64_t>();
  r.total_particles = j.at("total_particles").get<std::int64_t>();
  r.pair_evaluations = j.at("pair_evaluations").get<std::int64_t>();
  r.list_rebuilds = j.at("list_rebuilds").get<std::int64_t>();
  r.message = j.value("message", "");
  return r;
}

SphRunResult run_direct_sph(const Scene& scene, ParticleSystem& ps, const SphRunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto last_report = t0;
  SphEngine engine(scene, ps);
  SphRunResult res;
  res.total_particles = static_cast<std::int64_t>(ps.size());
  res.moving_particles = static_cast<std::int64_t>(engine.moving().size());
  engine.compute_accelerations();
  const auto observe = [&]() -> Eigen::VectorXd {
    if (opt.observable) return opt.observable(ps);
    Eigen::VectorXd v(engine.moving().size());
    for (std::size_t k = 0; k < engine.moving().size(); ++k) v[k] = ps.vx[engine.moving()[k]];
    return v;
  };
  Eigen::VectorXd reference = observe();
  auto relative_change = [&]() {
    const Eigen::VectorXd now = observe();
    const double mag = now.cwiseAbs().maxCoeff(), diff = (now - reference).cwiseAbs().maxCoeff();
    reference = now;
    return mag > 0.0 ? diff / mag : (diff > 0.0 ? 1.0 : 0.0);
  };
  res.status = "no_convergence";
  SnapshotSchedule snapshots(opt.snapshot_times);
  RunProgress estimate(opt.to_steady_state, opt.target_time, opt.max_time, opt.steady_tolerance);
  while (res.steps < opt.max_steps) {
    const double dt_full = engine.time_step(opt.kappa);  // reported; snapshots and the target time may shorten a step
    double dt = snapshots.clamp(res.time, dt_full);
    if (!opt.to_steady_state) {
      if (res.time >= opt.target_time * (1.0 - 1e-14)) {
        res.status = "target_time";
        break;
      }
      dt = std::min(dt, opt.target_time - res.time);
    }
    if (res.time >= opt.max_time) break;  // in both modes (validation refuses target_time > max_time)
    engine.step(dt);
    res.dt = dt_full;
    res.time += dt;
    ++res.steps;
    if (snapshots.due(res.time) && opt.on_snapshot) opt.on_snapshot(res.time, ps);
    if (res.steps % opt.steady_window == 0) {
      for (int a : engine.moving()) {
        if (!std::isfinite(ps.vx[a]) || !std::isfinite(ps.vy[a]) || !std::isfinite(ps.x[a]) || !std::isfinite(ps.y[a])) {
          res.status = "numerical_issue";
          break;
        }
      }
      if (res.status == "numerical_issue") break;
      res.last_relative_change = relative_change();
      if (opt.to_steady_state && res.steps > opt.steady_window && res.last_relative_change < opt.steady_tolerance) {
        res.status = "converged";
        break;
      }
      const auto now = clock::now();
      const ProgressEstimate done =
          estimate.update(res.time, res.last_relative_change, std::chrono::duration<double>(now - t0).count());
      if (opt.progress && std::chrono::duration<double>(now - last_report).count() >= opt.progress_seconds) {
        last_report = now;
        std::ostringstream os;
        os << "direct SPH: step " << res.steps << ", t = " << res.time << ", dt = " << dt_full
           << ", max|v| = " << engine.max_speed() << ", change over " << opt.steady_window
           << " steps = " << res.last_relative_change << "; " << RunProgress::describe(done);
        opt.progress(os.str());
      }
    }
  }
  if (res.status != "numerical_issue")
    for (int a : engine.moving())
      if (!std::isfinite(ps.vx[a]) || !std::isfinite(ps.vy[a]) || !std::isfinite(ps.x[a]) || !std::isfinite(ps.y[a])) {
        res.status = "numerical_issue";  // also between the periodic checks, e.g. at the target time
        break;
      }
  // Why a run is not a result (committed no_convergence rows had no message).
  std::ostringstream why;
  if (res.status == "numerical_issue") {
    why << "non-finite particle state at step " << res.steps << ", t = " << res.time;
  } else if (res.status == "no_convergence") {
    if (res.steps >= opt.max_steps) why << "max_steps = " << opt.max_steps << " reached at t = " << res.time;
    else why << "max_time = " << opt.max_time << " reached";
    if (opt.to_steady_state)
      why << " before steady state (last relative change " << res.last_relative_change << " over "
          << opt.steady_window << " steps, tolerance " << opt.steady_tolerance << ")";
    else
      why << " before target_time = " << opt.target_time;
  }
  res.message = why.str();
  res.wall_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  res.pair_evaluations = engine.pair_evaluations();
  res.list_rebuilds = engine.list_rebuilds();
  res.active_particles = static_cast<std::int64_t>(engine.active_count());
  return res;
}

ParamSchema sph_solver_schema() {
  const SphRunOptions d;  // the defaults
  return {
      number_param("kappa", d.kappa, "time-step coefficient kappa of (5.21)-(5.22)", 0.0, 1.0, true),
      string_param("mode", d.to_steady_state ? "steady" : "target_time",
                   "steady: run to steady state; target_time: run to target_time", {"steady", "target_time"}),
      number_param("target_time", d.target_time, "model time to reach in target_time mode", 0.0, {}),
      number_param("steady_tolerance", d.steady_tolerance, "steady state: max relative change of v_x over the window",
                   0.0, 1.0, true),
      integer_param("steady_window", d.steady_window, "steady state: window in steps", 1, {}),
      number_param("max_time", d.max_time, "give up (no_convergence) after this model time", 0.0, {}, true),
      integer_param("max_steps", d.max_steps, "give up after this many steps", 1, {}, IntegerKind::int64),
  };
}

void check_sph_solver(const json& s, const std::string& path) {
  if (s.at("mode") == "target_time" && !(s.at("target_time").get<double>() <= s.at("max_time").get<double>()))
    throw ConfigError(path + "/target_time", "target_time " + s.at("target_time").dump() + " exceeds max_time " +
                                                 s.at("max_time").dump() + " (raise max_time to run that long)");
}

SphRunOptions sph_run_options_from(const json& s) {
  SphRunOptions o;
  o.kappa = s.at("kappa").get<double>();
  o.to_steady_state = s.at("mode") == "steady";
  o.target_time = s.at("target_time").get<double>();
  o.steady_tolerance = s.at("steady_tolerance").get<double>();
  o.steady_window = s.at("steady_window").get<int>();
  o.max_time = s.at("max_time").get<double>();
  o.max_steps = s.at("max_steps").get<std::int64_t>();
  return o;
}

}  // namespace closurelab
