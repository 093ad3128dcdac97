// The built-in integrators (integrator.hpp): forward Euler, backward Euler with the Jacobian probed once, and Newton
// for the steady state of an affine rate.
#include "core/reduced/integrator.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <vector>

namespace closurelab {

void hold_entries(const CoarseRate& f, Eigen::VectorXd& u) {
  if (!f.held) return;
  for (Eigen::Index k = 0; k < u.size(); ++k)
    if ((*f.held)[static_cast<std::size_t>(k)]) u[k] = (*f.held_values)[k];
}

namespace {

bool is_held(const CoarseRate& f, Eigen::Index k) { return f.held && (*f.held)[static_cast<std::size_t>(k)]; }

}  // namespace

bool probe_affine(const RateFunction& fn, const CoarseRate& f, Eigen::Index n, Eigen::MatrixXd& jacobian,
                  Eigen::VectorXd& offset, Eigen::VectorXd& base, std::string& issue) {
  std::vector<Eigen::Index> free;
  for (Eigen::Index k = 0; k < n; ++k)
    if (!is_held(f, k)) free.push_back(k);
  base = Eigen::VectorXd::Zero(n);
  hold_entries(f, base);
  Eigen::VectorXd r0, r;
  if (!fn(base, r0, issue)) return false;
  jacobian = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index k : free) {
    Eigen::VectorXd u = base;
    u[k] = 1.0;
    if (!fn(u, r, issue)) return false;
    jacobian.col(k) = r - r0;
  }
  Eigen::VectorXd test = base;
  for (Eigen::Index k : free) test[k] = std::sin(1.0 + 3.7 * static_cast<double>(k));
  if (!fn(test, r, issue)) return false;
  const Eigen::VectorXd predicted = r0 + jacobian * (test - base);
  const double scale = std::max(r.cwiseAbs().maxCoeff(), 1e-300);
  if ((predicted - r).cwiseAbs().maxCoeff() > 1e-8 * scale) {
    issue.clear();
    return false;
  }
  offset = std::move(r0);
  return true;
}

namespace {

bool probe_affine_rate(const CoarseRate& f, Eigen::Index n, Eigen::MatrixXd& jacobian, Eigen::VectorXd& offset,
                       Eigen::VectorXd& base, std::string& issue) {
  return probe_affine(f.at, f, n, jacobian, offset, base, issue);
}

class ExplicitEuler : public Integrator {
 public:
  bool step(const CoarseRate& f, double dt, Eigen::VectorXd& u, std::string& issue) override {
    Eigen::VectorXd dudt;
    if (!f.at(u, dudt, issue)) return false;
    u += dt * dudt;
    hold_entries(f, u);
    return true;
  }
};

class BackwardEuler : public Integrator {
 public:
  bool needs_affine_rate() const override { return true; }
  void reset() override {
    jacobian_.resize(0, 0);
    lu_dt_ = std::numeric_limits<double>::quiet_NaN();
  }

  bool step(const CoarseRate& f, double dt, Eigen::VectorXd& u, std::string& issue) override {
    if (jacobian_.size() == 0 && !probe(f, u.size(), issue)) return false;
    // (I − dt J) u' = u + dt (c − J b) over the free entries; held entries keep their values. The factorisation is
    // kept while dt stays the same (a run at the viscous limit of (5.21)–(5.22) steps at one dt): the same bits as
    // factoring afresh, O(n²) a step instead of O(n³).
    const Eigen::Index n = u.size();
    std::vector<bool> held(static_cast<std::size_t>(n));
    for (Eigen::Index k = 0; k < n; ++k) held[static_cast<std::size_t>(k)] = is_held(f, k);
    if (!(dt == lu_dt_) || held != lu_held_) {
      Eigen::MatrixXd m = -dt * jacobian_;
      m.diagonal().array() += 1.0;
      for (Eigen::Index k = 0; k < n; ++k)
        if (is_held(f, k)) {
          m.row(k).setZero();
          m(k, k) = 1.0;
        }
      lu_.compute(m);
      lu_dt_ = dt;
      lu_held_ = held;
      offset_ = rate_offset_ - jacobian_ * base_;
    }
    Eigen::VectorXd rhs = u + dt * offset_;
    for (Eigen::Index k = 0; k < n; ++k)
      if (is_held(f, k)) rhs[k] = (*f.held_values)[k];
    u = lu_.solve(rhs);
    hold_entries(f, u);
    if (!u.allFinite()) {
      issue = "backward Euler step is not finite";
      return false;
    }
    return true;
  }

 private:
  bool probe(const CoarseRate& f, Eigen::Index n, std::string& issue) {
    if (!probe_affine_rate(f, n, jacobian_, rate_offset_, base_, issue)) {
      jacobian_.resize(0, 0);
      if (issue.empty())
        issue = "backward Euler needs a closure linear in the coarse velocity (fixed parameters); this one is not";
      return false;
    }
    lu_dt_ = std::numeric_limits<double>::quiet_NaN();
    return true;
  }

  Eigen::MatrixXd jacobian_;                 // ∂f/∂u over the free entries
  Eigen::VectorXd rate_offset_, base_;       // f(b) and b
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;  // of I − dt J (held rows the identity) at dt = lu_dt_
  double lu_dt_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<bool> lu_held_;  // the held entries it was factored with
  Eigen::VectorXd offset_;     // c − J b
};

// The steady state of an affine rate, f(u*) = 0 over the free entries, by Newton's method on the probed Jacobian:
// exact in one step for an affine f, then refined while the residual falls (round-off). No time step is taken.
class SteadyNewton : public Integrator {
 public:
  bool needs_affine_rate() const override { return true; }
  bool finds_steady_state() const override { return true; }
  bool step(const CoarseRate&, double, Eigen::VectorXd&, std::string& issue) override {
    issue = "newton finds the steady state and takes no time step (steady_state)";
    return false;
  }
  bool steady_state(const CoarseRate& f, Eigen::VectorXd& u, SteadySolveRecord& record, std::string& issue) override {
    const Eigen::Index n = u.size();
    Eigen::MatrixXd jacobian;
    Eigen::VectorXd offset, base;
    if (!probe_affine_rate(f, n, jacobian, offset, base, issue)) {
      if (issue.empty())
        issue = "newton needs a closure linear in the coarse velocity (fixed parameters); this one is not";
      return false;
    }
    record.rate_evaluations = n + 2;
    Eigen::MatrixXd m = jacobian;
    for (Eigen::Index k = 0; k < n; ++k)
      if (is_held(f, k)) {
        m.row(k).setZero();
        m(k, k) = 1.0;
      }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(m);
    u = base;
    hold_entries(f, u);
    Eigen::VectorXd r = offset;  // f(b)
    double scale = 0.0;
    for (record.iterations = 0; record.iterations < 5; ++record.iterations) {
      Eigen::VectorXd rhs = -r;
      for (Eigen::Index k = 0; k < n; ++k)
        if (is_held(f, k)) rhs[k] = 0.0;
      u += lu.solve(rhs);
      hold_entries(f, u);
      if (!f.at(u, r, issue)) return false;
      ++record.rate_evaluations;
      for (Eigen::Index k = 0; k < n; ++k)
        if (is_held(f, k)) r[k] = 0.0;
      const double residual = r.cwiseAbs().maxCoeff();
      if (record.iterations == 0) scale = std::max(jacobian.cwiseAbs().maxCoeff() * u.cwiseAbs().maxCoeff(), 1e-300);
      const double previous = record.iterations == 0 ? std::numeric_limits<double>::infinity() : record.residual;
      record.residual = residual / scale;
      if (!(record.residual < 0.5 * previous) && record.iterations > 0) break;  // round-off reached
    }
    ++record.iterations;
    if (!u.allFinite() || !(record.residual <= 1e-10)) {
      issue = "newton's steady state has a rate residual of " + std::to_string(record.residual) +
              " of |J| |u| (a singular or ill-conditioned steady system)";
      return false;
    }
    return true;
  }
};

}  // namespace

void register_integrators(Registry& r) {
  r.integrators.add(
      {"explicit", "forward Euler, the paper's (5.11)-(5.14): u += dt f(u), then the held nodes reset", {}},
      [](const json&) { return std::make_unique<ExplicitEuler>(); });
  r.integrators.add({"backward_euler",
                     "backward Euler, implicit in the whole rate: needs a closure linear in the coarse velocity (fixed "
                     "parameters; a parameter rule is served by the two-pass rule), whose Jacobian is probed once",
                     {}},
                    [](const json&) { return std::make_unique<BackwardEuler>(); });
  r.integrators.add({"newton",
                     "the steady state itself, no time step (mode steady, the column model): Newton's method on the "
                     "rate's Jacobian probed with unit vectors, exact in one step for a closure linear in the coarse "
                     "velocity (fixed parameters; a parameter rule is served by the two-pass rule), the residual "
                     "checked to 1e-10 of |J| |u|",
                     {}},
                    [](const json&) { return std::make_unique<SteadyNewton>(); });
  register_arkode_integrators(r);
}

}  // namespace closurelab
