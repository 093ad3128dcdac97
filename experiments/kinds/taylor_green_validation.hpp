#pragma once
// The direct SPH validation of the Taylor–Green scene (Scene::taylor_green; kind direct_sph_validation): the largest
// particle speed against the exact decay U e^{bt} at 20 equal fractions of the target time (PySPH taylor_green.py's
// linf error, |max|v| − U e^{bt}| / (U e^{bt})), the particles' velocities against the exact field at the end, and
// the spread of the number density (the particles' disorder). The run goes through the reference store
// (experiments/kinds/direct_reference.hpp) with its particles saved at those 20 times, so the stored entry (its
// particles.h5part: one Step#k per saved time, then the final state) is the direct reference of the transient that a
// reduced model of the vortex averages at each saved time.
#include <functional>
#include <string>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/params.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/validation_row.hpp"

namespace closurelab {

// Runs `scene` (which must declare taylor_green) to the solver's target_time through the reference store (the key:
// the cell's scene, kernel and solver sections, `observe_spacing` (absolute) and the saved times) and returns the
// kind's row: status, direct_sph (with reference_store: entry, reused, computed_by), scene_derived,
// errors.max_speed (times, computed, exact, relative_error, worst, final), errors.averaged_vs_averaged_exact (at the
// same times: the particles averaged onto the averaging mesh against the exact field times the window's symbol,
// max_rel and l2_rel relative to the averaged field's largest speed; worst_max_rel, window_factor,
// mesh_nodes_per_side), errors.particles_vs_exact,
// errors.number_density ((max − min)/mean, max |n/mean − 1|), cost.
json run_taylor_green_validation(const json& cfg, const Scene& scene, const AveragingKernel& kernel,
                                 double observe_spacing, const std::function<void(const std::string&)>& progress);

}  // namespace closurelab
