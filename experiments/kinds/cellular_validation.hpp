#pragma once
// The direct SPH validation of a cellular-flow scene (Scene::cellular_mode): particles and their Gaussian
// averages on a doubly periodic mesh against the exact A(t) · (sin kx cos ky, −cos kx sin ky) and its average.
#include "core/averaging/averaging_kernel.hpp"
#include "core/base/params.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"

namespace closurelab {

// The least-squares amplitude of the particles' velocities on the mode of wavenumber k:
// Σ v_p · φ(q_p) / Σ |φ(q_p)|² over the moving particles.
double fitted_cellular_amplitude(const ParticleSystem& ps, double k);

// The largest displacement of a moving particle from its lattice site (scene.make_particles(), same order;
// minimum image), in lattice spacings ε'.
double max_displacement_in_spacings(const Scene& scene, const ParticleSystem& ps);

// Runs the direct SPH of `scene` (which must declare cellular_mode) with `options` and returns the row of the
// direct_sph_validation kind: status, direct_sph, scene_derived, errors (fitted amplitude, particles and the
// mesh averages against the exact field and its average at the final time), max displacement and cost.
json run_cellular_validation(const Scene& scene, const AveragingKernel& kernel, SphRunOptions options,
                             double mesh_spacing);

}  // namespace closurelab
