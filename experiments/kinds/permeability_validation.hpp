#pragma once
// The direct SPH validation of a porous-medium scene (Scene::permeability, e.g. cylinder-lattice): the run to
// steady state judged by the permeability itself, the Darcy permeability k = μ⟨u_x⟩/(ρ g) against the scene's
// reference, the particles' displacements and density deviations.
#include "core/base/params.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"

namespace closurelab {

// k = μ ⟨u_x⟩ / (ρ g): ⟨u_x⟩ the x-velocity averaged over the whole cell, each lattice site an area ε'² and the
// solid counting zero (Σ_fluid v_x ε'² / (L_x L_y)).
double darcy_permeability(const Scene& scene, const ParticleSystem& ps);

// Runs the direct SPH of `scene` (which must declare permeability) with `options`, its steady state decided by
// the relative change of k over the solver's steady_window (options.observable is replaced), and returns the
// row of the direct_sph_validation kind: status, direct_sph, scene_derived, errors (k against the reference, the
// effective solid size, the k history), the particles' largest displacement from their lattice sites and from the
// lattice, their density deviation, the Reynolds and Mach numbers, and the cost.
json run_permeability_validation(const Scene& scene, SphRunOptions options);

}  // namespace closurelab
