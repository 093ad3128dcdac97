#pragma once
#include <memory>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
// "quadrature_convergence" (Appendix C): the error of a stress quadrature (normally the coarse one, (5.27))
// against the exact pair sum (2.13) for a given velocity field on a scene, with both quadratures' costs.
std::unique_ptr<ExperimentKind> make_quadrature_convergence_experiment();
}  // namespace closurelab
