#pragma once
#include <memory>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
// "direct_sph_validation": direct SPH of a scene to steady state, averaged, compared with the analytic
// solution and its average (errors in the interior and the wall band separately) with its cost.
std::unique_ptr<ExperimentKind> make_sph_validation_experiment();
}  // namespace closurelab
