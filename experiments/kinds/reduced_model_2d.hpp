#pragma once
#include <memory>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
// "reduced_model_2d": the two-dimensional coarse solver (core/reduced/meso_solver_2d.hpp) on a cellular scene,
// against the exact field, its average and the averaged direct SPH of the same box (from the reference store),
// with the transient, the cost and the speed-up.
std::unique_ptr<ExperimentKind> make_reduced_model_2d_experiment();
}  // namespace closurelab
