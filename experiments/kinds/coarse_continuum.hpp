#pragma once
#include <memory>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
// "coarse_continuum_2d": the coarse continuum Navier–Stokes baseline (core/continuum/coarse_navier_stokes_2d.hpp)
// on the 2D reduced model's mesh, against the exact field, its average and the averaged direct SPH of the same box
// (from the reference store), with the transient, the cost and the speed-up, in reduced_model_2d's columns
// (experiments/kinds/coarse_continuum.cpp).
std::unique_ptr<ExperimentKind> make_coarse_continuum_2d_experiment();
}  // namespace closurelab
