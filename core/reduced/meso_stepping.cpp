// One step of the reduced model: the solver's Integrator (core/reduced/integrator.hpp) advances v̄ by the rate
// (5.11)–(5.13) at its current value, the held nodes ((5.14), or the boundary oracle's) at their values.
#include "core/reduced/meso_solver.hpp"

namespace closurelab {

bool MesoSolver::step(double dt, std::string& issue) {
  const CoarseRate f{[this](const Eigen::VectorXd& u, Eigen::VectorXd& dvdt, std::string& why) {
                       v_ = u;
                       return rate(dvdt, why);
                     },
                     &held_, &held_values_};
  Eigen::VectorXd u = v_;
  const bool ok = integrator_.step(f, dt, u, issue);
  v_ = std::move(u);
  return ok;
}

}  // namespace closurelab
