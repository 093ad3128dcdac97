#pragma once
// The spec sections that the reduced-model kinds share (reduced_model in 1D, reduced_model_2d): the closure
// and the direct SPH reference.
#include "core/base/params.hpp"

namespace closurelab {

// "closure": the registered deconvolver with its parameters, the discretization of R_η (§4.2), the noise level.
ParamSchema closure_schema();
// "reference": whether to run the direct SPH of the same scene, its solver section, the observe-mesh spacing.
ParamSchema reference_schema();

}  // namespace closurelab
