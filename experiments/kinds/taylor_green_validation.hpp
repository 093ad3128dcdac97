#pragma once
// The direct SPH validation of the Taylor–Green scene (Scene::taylor_green; kind direct_sph_validation): the largest
// particle speed against the exact decay U e^{bt} at 20 equal fractions of the target time (PySPH taylor_green.py's
// linf error, |max|v| − U e^{bt}| / (U e^{bt})), the particles' velocities against the exact field at the end, and
// the spread of the number density (the particles' disorder).
#include "core/base/params.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"

namespace closurelab {

// Runs `scene` (which must declare taylor_green) to options.target_time and returns the kind's row: status,
// direct_sph, scene_derived, errors.max_speed (times, computed, exact, relative_error, worst, final),
// errors.particles_vs_exact, errors.number_density ((max − min)/mean, max |n/mean − 1|), cost.
json run_taylor_green_validation(const Scene& scene, SphRunOptions options);

}  // namespace closurelab
