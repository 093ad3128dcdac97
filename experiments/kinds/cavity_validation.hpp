#pragma once
// The direct SPH validation of the lid-driven cavity (Scene::cavity; kind direct_sph_validation): the velocity on
// the two centre lines at the end of the run against the steady profiles of Ghia, Ghia & Shin (1982)
// (core/scenes/ghia_cavity.hpp), as PySPH's cavity.py post-processing compares them, and how steady the run is. The
// run goes through the reference store with its particles saved at 20 equal fractions of the target time, so the
// stored entry is also the direct reference of the cavity's transient.
#include <functional>
#include <string>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/params.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

// The Shepard interpolation of the particles' velocity at (x, y) with the scene's SPH kernel:
// Σ_b v_b W(x − x_b) / Σ_b W(x − x_b) over every particle, the walls carrying their prescribed velocity (PySPH's
// Interpolator, method 'shepard', sums its solid arrays likewise). (0, 0) where no particle is within the support.
Vec2 shepard_velocity(const ParticleSystem& ps, const Scene& scene, double x, double y);

// Runs `scene` (which must declare cavity, at a Reynolds number Ghia tabulates) to the solver's target_time through
// the reference store and returns the kind's row: status, direct_sph (with reference_store), scene_derived,
// errors.centrelines (Ghia's points: y, u_ghia and u at x = L/2; x, v_ghia and v at y = L/2, u and v the mean over
// the last five saved times (mean_over_times: the first and last), u_end and v_end at the end; max_abs_u, max_abs_v
// and worst, the largest |difference| of the mean from Ghia's over the points inside the cavity, in units of the lid
// speed; worst_end the same at the end; largest_change_between_saved_times, how far the profiles move between
// successive saved times of the window), errors.number_density (the disorder: (max − min)/mean and max |n/mean − 1|
// over the fluid), cost.
json run_cavity_validation(const json& cfg, const Scene& scene, const AveragingKernel& kernel, double observe_spacing,
                           const std::function<void(const std::string&)>& progress);

}  // namespace closurelab
