#pragma once
#include <memory>

#include "core/reduced/meso_solver.hpp"
#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
// "reduced_model": the coarse solver with a deconvolution closure and a stress quadrature, against the
// analytic solution, its average, and the averaged direct SPH of the same scene (run in the same process,
// which gives the speed-up).
std::unique_ptr<ExperimentKind> make_reduced_model_experiment();
// "reduced_model" for every scene: the three reduced models behind one kind, chosen by the cell's "model" or by the
// scene (experiments/kinds/reduced_model_models.cpp); the 1D kind above is its "column" model.
std::unique_ptr<ExperimentKind> make_reduced_model_any_geometry_experiment();
}  // namespace closurelab
