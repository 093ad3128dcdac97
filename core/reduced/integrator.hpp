#pragma once
// The integrator family (DESIGN.md §2): how a stepped reduced model's coarse state advances by one step, apart from
// the model's right-hand side (PETSc's TS apart from its RHS function). The model offers its rate f(u) = du/dt and
// the entries it holds (the wall nodes (5.6)/(5.14), or the boundary oracle's); the integrator advances u.
// Built-ins (registered by register_integrators, named as a spec's solver.time_integration names them):
//   explicit        forward Euler, the paper's (5.11)–(5.14): u += dt f(u), then the held entries reset;
//   backward_euler  implicit in the whole rate, for a rate affine in u (a closure with fixed parameters): the
//                   Jacobian probed once with unit vectors and checked for affinity at a second point, then
//                   (I − dt J) u' = u + dt (f(b) − J b) over the free entries, b the probe's base.
//   newton          no step: the steady state f(u*) = 0 itself, for a rate affine in u (the Jacobian probed as
//                   backward Euler probes it, one solve, refined while the residual falls); a model in mode steady
//                   calls steady_state() instead of its time loop (the column model; the 2D models refuse it);
//   arkode_erk      SUNDIALS ARKODE ERKStep (integrator_arkode.cpp): u integrated from t to t + dt by an embedded
//                   explicit Runge–Kutta pair with local error control (rtol, atol; internal steps as needed, a stop
//                   time at t + dt), or method forward_euler: one stage at the fixed step dt (the explicit step
//                   through ARKODE);
//   arkode_imex     SUNDIALS ARKODE ARKStep: additive Runge–Kutta with error control, the rate's `stiff` part
//                   implicit (Newton; its systems by matrix-free GMRES with difference-quotient J·v, or, with
//                   linear_solver dense, by Eigen's LU of I − γJ, J the implicit part's Jacobian probed once: an
//                   affine implicit part, a closure with fixed parameters), the rest explicit; a model that offers
//                   no split is integrated implicitly whole (the pair's DIRK table).
// The ARKODE ones hold the held entries at rate zero during the step and reset them after it, as `explicit` does;
// they need no affine rate. Parameters (a spec's time_integration {"name": ..., ...}) are each entry's schema.
// An instance serves one model (backward Euler keeps the Jacobian it probed on its first step; an ARKODE one its
// SUNDIALS context and memory, and the step size its error control chose last).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/base/registry.hpp"

namespace closurelab {

// du/dt (or a part of it) at u; false on a numerical issue, said in `issue`.
using RateFunction = std::function<bool(const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string& issue)>;

// What a model offers an integrator.
struct CoarseRate {
  // du/dt at u.
  RateFunction at;
  // The entries a step leaves at their held values (null: none is held).
  const std::vector<bool>* held = nullptr;
  const Eigen::VectorXd* held_values = nullptr;
  // Optional, for an IMEX integrator (arkode_imex): the part of the rate treated implicitly (the stiff, viscous
  // part), same signature as `at`. Null: no split (arkode_imex then treats the whole rate implicitly).
  RateFunction stiff{};
  // Optional with `stiff`: the explicit part, at − stiff, when the model computes it apart (null: at − stiff,
  // one call of each).
  RateFunction nonstiff{};
};

// What a steady solve (Integrator::steady_state) did.
struct SteadySolveRecord {
  int iterations = 0;         // Newton steps
  long rate_evaluations = 0;  // the Jacobian's probes included
  double residual = 0.0;      // max |f(u*)| over the free entries / (max|J| max|u*|)
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Advances u (held entries at their values) by dt; false on a numerical issue, said in `issue`.
  virtual bool step(const CoarseRate& f, double dt, Eigen::VectorXd& u, std::string& issue) = 0;
  // Whether the integrator is right only for a rate affine in u (a closure linear in the coarse velocity: fixed
  // parameters, no Krylov iterate); such a spec is checked at validation (check_implicit_closure).
  virtual bool needs_affine_rate() const { return false; }
  // Whether it is right only for a closure linear in the coarse state (checked at validation as needs_affine_rate
  // is): an integrator that needs an affine rate, or one that probes the Jacobian of the implicit part alone
  // (arkode_imex with linear_solver dense), which leaves the explicit part free to be nonlinear.
  virtual bool needs_linear_closure() const { return needs_affine_rate(); }
  // The model's rate or held entries changed (e.g. oracles switched on): forget what was learned of them.
  virtual void reset() {}
  // Whether it finds the steady state itself (steady_state) rather than stepping: a model in mode steady then calls
  // steady_state instead of its time loop.
  virtual bool finds_steady_state() const { return false; }
  virtual bool steady_state(const CoarseRate&, Eigen::VectorXd&, SteadySolveRecord&, std::string& issue) {
    issue = "this integrator steps; it does not find the steady state itself";
    return false;
  }
};

// The held entries of u set to their values.
void hold_entries(const CoarseRate& f, Eigen::VectorXd& u);

// Probes fn (f's rate or a part of it) as an affine map, fn(u) = offset + J (u − base) over f's free entries: unit
// vectors from base (zero, held entries held), the affinity checked at a second point (within 1e-8 of the rate's
// peak). False with `issue` empty when fn is not affine (a parameter rule, an iteration stopped by a tolerance, a
// nonlinear term), with the model's issue when an evaluation failed. Columns of held entries are zero.
bool probe_affine(const RateFunction& fn, const CoarseRate& f, Eigen::Index n, Eigen::MatrixXd& jacobian,
                  Eigen::VectorXd& offset, Eigen::VectorXd& base, std::string& issue);

// Adds the built-in integrators to r.integrators (the ARKODE ones by register_arkode_integrators).
void register_integrators(Registry& r);
void register_arkode_integrators(Registry& r);

}  // namespace closurelab
