#pragma once
#include <memory>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
// "reduced_model_2d": the two-dimensional coarse solver (core/reduced/meso_solver_2d.hpp) on a cellular scene,
// against the exact field, its average and the averaged direct SPH of the same box (from the reference store),
// with the transient, the cost and the speed-up.
std::unique_ptr<ExperimentKind> make_reduced_model_2d_experiment();
// "reduced_model_2d_force_density": the linearised force-density model with solids (core/reduced/force_density_2d.hpp)
// on a scene periodic in x and periodic or walled in y (the cylinder lattice and channel, the channels as one column,
// the cellular flow), against the averaged direct SPH at steady state, with the
// Darcy permeability, the cost and the speed-up (experiments/kinds/reduced_model_force_density_2d.cpp).
std::unique_ptr<ExperimentKind> make_reduced_model_force_density_2d_experiment();
}  // namespace closurelab
