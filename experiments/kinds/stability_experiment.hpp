#pragma once
// Experiment kind "deconvolution_stability": one case of the hard-case suite per cell.
#include <memory>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
std::unique_ptr<ExperimentKind> make_stability_experiment();
}
