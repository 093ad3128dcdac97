// One step of the reduced model: the solver's Integrator (core/reduced/integrator.hpp) advances v̄ by the rate
// (5.11)–(5.13) at its current value, the held nodes ((5.14), or the boundary oracle's) at their values; or, under an
// integrator that finds the steady state itself (newton), that state in one call instead of the time loop; and the
// run, by the shared time loop (core/base/time_loop.hpp) or that call, with its result.
#include <chrono>
#include <ctime>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/reduced/meso_solver.hpp"

namespace closurelab {

CoarseRate MesoSolver::coarse_rate() {
  return CoarseRate{[this](const Eigen::VectorXd& u, Eigen::VectorXd& dvdt, std::string& why) {
                      v_ = u;
                      return rate(dvdt, why);
                    },
                    &held_, &held_values_};
}

bool MesoSolver::step(double dt, std::string& issue) {
  const CoarseRate f = coarse_rate();
  Eigen::VectorXd u = v_;
  const bool ok = integrator_.step(f, dt, u, issue);
  v_ = std::move(u);
  return ok;
}

MesoResult MesoSolver::steady_state() {
  // The integrator finds the steady state itself (newton): no time step, no loop; the record's residual stands in
  // for the loop's last relative change.
  if (!opt_.to_steady_state)
    throw ConfigError("/solver/time_integration", "newton finds the steady state: mode steady");
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  const CoarseRate f = coarse_rate();
  Eigen::VectorXd u = v_;
  SteadySolveRecord record;
  std::string issue;
  const bool ok = integrator_.steady_state(f, u, record, issue);
  v_ = std::move(u);
  MesoResult res;
  if (ok) {
    std::string why;
    res.status = coarse_state_ok(v_.allFinite(), v_.allFinite() ? v_.cwiseAbs().maxCoeff() : 0.0, scene_.analytic_peak,
                                 opt_.divergence_factor, why)
                     ? Status::converged
                     : Status::numerical_issue;
    res.message = why;
  } else {
    res.status = Status::numerical_issue;
    res.message = issue;
  }
  res.last_relative_change = record.residual;
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.cpu_seconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  if (opt_.progress)
    opt_.progress("reduced model: steady state by newton, " + std::to_string(record.iterations) + " iteration(s), " +
                  std::to_string(record.rate_evaluations) + " rate evaluations, residual " +
                  std::to_string(record.residual));
  return finished(std::move(res));
}

MesoResult MesoSolver::run() {
  if (integrator_.finds_steady_state()) return steady_state();
  SteppedModel model;
  model.name = "reduced model";
  model.time_step = [&] { return time_step(); };
  model.step = [&](double dt, std::string& issue) { return step(dt, issue); };
  model.observe = [&] { return v_; };
  model.check_state = [&](std::string& issue) {
    const bool finite = v_.allFinite();
    return coarse_state_ok(finite, finite ? v_.cwiseAbs().maxCoeff() : 0.0, scene_.analytic_peak,
                           opt_.divergence_factor, issue);
  };
  if (opt_.on_snapshot) model.snapshot = [&](double t) { opt_.on_snapshot(t, reported_velocity()); };
  model.describe = [&] {
    std::ostringstream os;
    os << "max|v| = " << v_.cwiseAbs().maxCoeff();
    return os.str();
  };
  MesoResult res;
  static_cast<TimeLoopResult&>(res) = run_time_loop(model, opt_);
  return finished(std::move(res));
}

MesoResult MesoSolver::finished(MesoResult res) {
  res.y = coarse_.nodes();
  res.v = reported_velocity();
  res.deconvolution_matvecs = matvecs_;
  res.parameter_choice = choice_;
  res.deconvolution_issues = deconvolution_issues_;
  res.deconvolution_seconds = deconv_seconds_;
  res.quadrature_seconds = quad_seconds_;
  res.quadrature_cost = quad_cost_;
  return res;
}

}  // namespace closurelab
