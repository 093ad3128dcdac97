// The built-in integrators (integrator.hpp): forward Euler and backward Euler with the Jacobian probed once.
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
  // The rate is affine for a closure with fixed parameters, f(u) = c + J (u − b) over the free entries (held entries
  // at their values). Probed once with unit vectors from b (zero, held entries held); a probe at a second point
  // checks the affinity (a parameter rule or an iteration stopped by a tolerance breaks it).
  bool probe(const CoarseRate& f, Eigen::Index n, std::string& issue) {
    std::vector<Eigen::Index> free;
    for (Eigen::Index k = 0; k < n; ++k)
      if (!is_held(f, k)) free.push_back(k);
    Eigen::VectorXd base = Eigen::VectorXd::Zero(n);
    hold_entries(f, base);
    Eigen::VectorXd r0, r;
    if (!f.at(base, r0, issue)) return false;
    Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index k : free) {
      Eigen::VectorXd u = base;
      u[k] = 1.0;
      if (!f.at(u, r, issue)) return false;
      jacobian.col(k) = r - r0;
    }
    Eigen::VectorXd test = base;
    for (Eigen::Index k : free) test[k] = std::sin(1.0 + 3.7 * static_cast<double>(k));
    if (!f.at(test, r, issue)) return false;
    const Eigen::VectorXd predicted = r0 + jacobian * (test - base);
    const double scale = std::max(r.cwiseAbs().maxCoeff(), 1e-300);
    if ((predicted - r).cwiseAbs().maxCoeff() > 1e-8 * scale) {
      issue = "backward Euler needs a closure linear in the coarse velocity (fixed parameters); this one is not";
      return false;
    }
    jacobian_ = std::move(jacobian);
    rate_offset_ = std::move(r0);
    base_ = std::move(base);
    lu_dt_ = std::numeric_limits<double>::quiet_NaN();
    return true;
  }

  Eigen::MatrixXd jacobian_;              // ∂f/∂u over the free entries
  Eigen::VectorXd rate_offset_, base_;    // f(b) and b
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;  // of I − dt J (held rows the identity) at dt = lu_dt_
  double lu_dt_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<bool> lu_held_;                // the held entries it was factored with
  Eigen::VectorXd offset_;                   // c − J b
};

}  // namespace

void register_integrators(Registry& r) {
  r.integrators.add({"explicit", "forward Euler, the paper's (5.11)-(5.14): u += dt f(u), then the held nodes reset", {}},
                    [](const json&) { return std::make_unique<ExplicitEuler>(); });
  r.integrators.add({"backward_euler",
                     "backward Euler, implicit in the whole rate: needs a closure linear in the coarse velocity (fixed "
                     "parameters; a parameter rule is served by the two-pass rule), whose Jacobian is probed once",
                     {}},
                    [](const json&) { return std::make_unique<BackwardEuler>(); });
  register_arkode_integrators(r);
}

}  // namespace closurelab
