// One step of the reduced model: forward Euler (5.11)–(5.14), or backward Euler with the rate's Jacobian
// probed once (MesoSolverOptions::time_integration).
#include <Eigen/LU>
#include <cmath>

#include "core/reduced/meso_solver.hpp"

namespace closurelab {

// The closure is linear in v̄ for the fixed-parameter strategies, so the rate is affine, r(v̄) = c + J v̄ over
// the evolved nodes (held nodes fixed at their values). Probed once with unit vectors; a probe at a second
// point checks the affinity (a parameter rule or an iteration stopped by a tolerance breaks it).
bool MesoSolver::probe_jacobian(std::string& issue) {
  const int n = coarse_.count;
  const Eigen::VectorXd saved = v_;
  std::vector<int> free;
  for (int k = 0; k < n; ++k)
    if (!held_[k]) free.push_back(k);
  v_.setZero();
  hold_nodes();
  const Eigen::VectorXd base = v_;
  Eigen::VectorXd r0, r;
  if (!rate(r0, issue)) return false;
  jacobian_ = Eigen::MatrixXd::Zero(n, n);
  for (int k : free) {
    v_ = base;
    v_[k] = 1.0;
    if (!rate(r, issue)) return false;
    jacobian_.col(k) = r - r0;
  }
  rate_offset_ = r0;
  Eigen::VectorXd test = base;
  for (int k : free) test[k] = std::sin(1.0 + 3.7 * k);
  v_ = test;
  if (!rate(r, issue)) return false;
  const Eigen::VectorXd predicted = rate_offset_ + jacobian_ * (test - base);
  const double scale = std::max(r.cwiseAbs().maxCoeff(), 1e-300);
  v_ = saved;
  if ((predicted - r).cwiseAbs().maxCoeff() > 1e-8 * scale) {
    issue = "backward Euler needs a closure linear in the coarse velocity (fixed parameters); this one is not";
    return false;
  }
  jacobian_base_ = base;
  return true;
}

bool MesoSolver::step(double dt, std::string& issue) {
  if (opt_.time_integration == TimeIntegration::backward_euler) {
    if (jacobian_.size() == 0 && !probe_jacobian(issue)) return false;
    // (I − dt J) v^{n+1} = v^n + dt (c − J v_held) over the evolved nodes; held nodes keep their values.
    const int n = coarse_.count;
    Eigen::MatrixXd m = -dt * jacobian_;
    m.diagonal().array() += 1.0;
    Eigen::VectorXd rhs = v_ + dt * (rate_offset_ - jacobian_ * jacobian_base_);
    for (int k = 0; k < n; ++k)
      if (held_[k]) {
        m.row(k).setZero();
        m(k, k) = 1.0;
        rhs[k] = held_values_[k];
      }
    v_ = m.partialPivLu().solve(rhs);
    hold_nodes();
    if (!v_.allFinite()) {
      issue = "backward Euler step is not finite";
      return false;
    }
    return true;
  }
  Eigen::VectorXd dvdt;
  if (!rate(dvdt, issue)) return false;
  v_ += dt * dvdt;
  hold_nodes();  // (5.14), or the boundary oracle
  return true;
}


}  // namespace closurelab
