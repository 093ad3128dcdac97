#include "core/base/time_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/repeated_timing.hpp"
#include "core/base/run_progress.hpp"
#include "core/base/snapshot_schedule.hpp"

namespace closurelab {

json TimeLoopResult::to_json() const {
  json j = {{"status", to_string(status)},
            {"steps", steps},
            {"time", time},
            {"dt", dt},
            {"wall_seconds", wall_seconds},
            {"cpu_seconds", cpu_seconds},
            {"last_relative_change", last_relative_change}};
  if (!message.empty()) j["message"] = message;
  return j;
}

namespace {

std::string give_up_message(const TimeLoopResult& r, const TimeLoopOptions& o) {
  std::ostringstream why;
  if (r.steps >= o.max_steps)
    why << "max_steps = " << o.max_steps << " reached at t = " << r.time;
  else
    why << "max_time = " << o.max_time << " reached";
  if (o.to_steady_state)
    why << " before steady state (last relative change " << r.last_relative_change << " over " << o.steady_window
        << " steps, tolerance " << o.steady_tolerance << ")";
  else
    why << " before target_time = " << o.target_time;
  return why.str();
}

}  // namespace

TimeLoopResult run_time_loop(const SteppedModel& model, const TimeLoopOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double cpu0 = process_cpu_seconds();
  auto last_report = t0;
  TimeLoopResult res;
  Eigen::VectorXd reference = model.observe();
  const auto relative_change = [&]() {
    const Eigen::VectorXd now = model.observe();
    const double mag = now.size() ? now.cwiseAbs().maxCoeff() : 0.0;
    const double diff = now.size() ? (now - reference).cwiseAbs().maxCoeff() : 0.0;
    reference = now;
    return mag > 0.0 ? diff / mag : (diff > 0.0 ? 1.0 : 0.0);
  };
  const auto fail = [&](const std::string& issue) {
    res.status = Status::numerical_issue;
    std::ostringstream os;
    os << issue << " (step " << res.steps << ", t = " << res.time << ")";
    res.message = os.str();
  };
  SnapshotSchedule snapshots(opt.snapshot_times);
  RunProgress estimate(opt.to_steady_state, opt.target_time, opt.max_time, opt.steady_tolerance);
  std::string issue;
  while (res.steps < opt.max_steps) {
    const double dt_full = model.time_step();  // reported; snapshots and the target time may shorten a step
    double dt = snapshots.clamp(res.time, dt_full);
    if (!opt.to_steady_state) {
      if (res.time >= opt.target_time * (1.0 - 1e-14)) {
        res.status = Status::target_time;
        break;
      }
      dt = std::min(dt, opt.target_time - res.time);
    }
    if (res.time >= opt.max_time) break;  // in both modes (validation refuses target_time > max_time)
    if (!model.step(dt, issue)) {
      fail(issue);
      break;
    }
    res.dt = dt_full;
    res.time += dt;
    ++res.steps;
    if (snapshots.due(res.time) && model.snapshot) model.snapshot(res.time);
    if (res.steps % opt.steady_window != 0) continue;
    if (!model.check_state(issue)) {
      fail(issue);
      break;
    }
    res.last_relative_change = relative_change();
    if (opt.to_steady_state && res.steps > opt.steady_window && res.last_relative_change < opt.steady_tolerance) {
      res.status = Status::converged;
      break;
    }
    const auto now = clock::now();
    const ProgressEstimate done =
        estimate.update(res.time, res.last_relative_change, std::chrono::duration<double>(now - t0).count());
    if (opt.progress && std::chrono::duration<double>(now - last_report).count() >= opt.progress_seconds) {
      last_report = now;
      std::ostringstream os;
      os << model.name << ": step " << res.steps << ", t = " << res.time << ", dt = " << dt_full;
      if (model.describe) os << ", " << model.describe();
      os << ", change over " << opt.steady_window << " steps = " << res.last_relative_change << "; "
         << RunProgress::describe(done);
      opt.progress(os.str());
    }
  }
  // Also between the periodic checks, e.g. at the target time.
  if (res.status != Status::numerical_issue && !model.check_state(issue)) fail(issue);
  if (res.status == Status::no_convergence) res.message = give_up_message(res, opt);
  res.wall_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  res.cpu_seconds = process_cpu_seconds() - cpu0;
  return res;
}

ParamSchema time_loop_schema(const TimeLoopOptions& d) {
  return {
      string_param("mode", d.to_steady_state ? "steady" : "target_time",
                   "steady: run to steady state; target_time: run to target_time", {"steady", "target_time"}),
      number_param("target_time", d.target_time, "model time to reach in target_time mode", 0.0, {}),
      number_param("steady_tolerance", d.steady_tolerance,
                   "steady state: max relative change of the observed velocity over the window", 0.0, 1.0, true),
      integer_param("steady_window", d.steady_window, "steady state: window in steps", 1, {}),
      number_param("max_time", d.max_time, "give up (no_convergence) after this model time", 0.0, {}, true),
      integer_param("max_steps", d.max_steps, "give up after this many steps", 1, {}, IntegerKind::int64),
  };
}

void read_time_loop(const json& s, TimeLoopOptions& o) {
  o.to_steady_state = s.at("mode") == "steady";
  o.target_time = s.at("target_time").get<double>();
  o.steady_tolerance = s.at("steady_tolerance").get<double>();
  o.steady_window = s.at("steady_window").get<int>();
  o.max_time = s.at("max_time").get<double>();
  o.max_steps = s.at("max_steps").get<std::int64_t>();
}

void check_time_loop(const json& s, const std::string& path) {
  if (s.at("mode") == "target_time" && !(s.at("target_time").get<double>() <= s.at("max_time").get<double>()))
    throw ConfigError(path + "/target_time", "target_time " + s.at("target_time").dump() + " exceeds max_time " +
                                                 s.at("max_time").dump() + " (raise max_time to run that long)");
  if (s.at("mode") != "steady") return;
  const double tol = s.at("steady_tolerance").get<double>();
  if (tol > kMaxSteadyTolerance)
    throw ConfigError(path + "/steady_tolerance",
                      "steady_tolerance " + s.at("steady_tolerance").dump() + " is above " + json(kMaxSteadyTolerance).dump() +
                          ": a change that large over a window cannot mean steady state");
  // The test needs two windows (a change between window ends, the first at step W).
  if (2 * s.at("steady_window").get<std::int64_t>() > s.at("max_steps").get<std::int64_t>())
    throw ConfigError(path + "/steady_window", "steady_window " + s.at("steady_window").dump() +
                                                   " needs at least twice as many steps to find steady state, more "
                                                   "than max_steps = " + s.at("max_steps").dump());
  if (!s.contains("kappa")) return;
  const double reach = s.at("steady_window").get<double>() * s.at("kappa").get<double>();
  if (reach < 1.0) {
    std::ostringstream os;
    os << "steady_window " << s.at("steady_window").get<int>() << " steps at kappa " << s.at("kappa").get<double>()
       << " spans at most " << reach << " viscous times of the spacing (rho h^2 / mu): too short to show any "
       << "relaxation, so it cannot mean steady state; use steady_window >= " << std::setprecision(15) << std::ceil(1.0 / s.at("kappa").get<double>())
       << " steps at this kappa";
    throw ConfigError(path + "/steady_window", os.str());
  }
}

double steady_distance_bound(const json& s, double spacings) {
  const double x = std::numbers::pi * std::numbers::pi * s.at("steady_window").get<double>() *
                   s.at("kappa").get<double>() / (spacings * spacings);
  return s.at("steady_tolerance").get<double>() / -std::expm1(-x);
}

void check_steady_reach(const json& s, double spacings, const std::string& path) {
  if (s.at("mode") != "steady" || !(spacings > 0.0)) return;
  const double d = steady_distance_bound(s, spacings);
  if (d <= kMaxSteadyDistance) return;
  std::ostringstream os;
  os << "steady_window " << s.at("steady_window").get<int>() << " steps at kappa " << s.at("kappa").get<double>()
     << " with steady_tolerance " << s.at("steady_tolerance").get<double>() << " across a relaxation length of "
     << spacings << " spacings: a run called steady could still be " << d * 100 << " % from steady state (at least; at most "
     << kMaxSteadyDistance * 100 << " % is allowed); lengthen the window or tighten the tolerance";
  throw ConfigError(path + "/steady_window", os.str());
}

void check_steps_reach_target(const json& s, double max_dt, const std::string& path) {
  if (s.at("mode") != "target_time") return;
  const double steps = s.at("target_time").get<double>() / max_dt;
  const auto max_steps = s.at("max_steps").get<std::int64_t>();
  if (!(steps > static_cast<double>(max_steps))) return;
  std::ostringstream os;
  os << "target_time " << s.at("target_time").get<double>() << " needs at least " << steps << " steps of at most dt = "
     << max_dt << ", more than max_steps = " << max_steps << ": the run could only give up; shorten target_time or "
     << "raise max_steps";
  throw ConfigError(path + "/target_time", os.str());
}

}  // namespace closurelab
