#pragma once
// The direct SPH reference of a scene: run to steady state (the paper's criterion applied to the averaged
// velocity on a column mesh) or to a target time; shared by the validation and reduced-model experiments.
#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"

namespace closurelab {

struct DirectReference {
  ParticleSystem particles;  // the final state
  SphRunResult run;
};

DirectReference run_direct_reference(const Scene& scene, const AveragingKernel& kernel, SphRunOptions options,
                                     const TensorMesh2D& observe_mesh);

}  // namespace closurelab
