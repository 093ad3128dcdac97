#pragma once
// The spec sections that the reduced-model kinds share (reduced_model in 1D, reduced_model_2d): the closure
// and the direct SPH reference.
#include <string>

#include "core/base/params.hpp"

namespace closurelab {

// "closure": the registered deconvolver with its parameters, the discretization of R_η (§4.2), the noise level.
ParamSchema closure_schema();
// "reference": whether to run the direct SPH of the same scene, its solver section, the observe-mesh spacing.
ParamSchema reference_schema();
// A transient section's snapshot times (`times`, an array at JSON path `path`): finite, positive, ascending;
// ConfigError at the first that is not.
void check_snapshot_times(const json& times, const std::string& path);

}  // namespace closurelab
