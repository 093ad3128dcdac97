#include "experiments/kinds/direct_reference.hpp"

#include "core/averaging/averaging.hpp"

namespace closurelab {

DirectReference run_direct_reference(const Scene& scene, const AveragingKernel& kernel, SphRunOptions options,
                                     const TensorMesh2D& observe_mesh) {
  DirectReference ref{scene.make_particles(), {}};
  options.observable = [&](const ParticleSystem& p) {
    return average_particles(p, scene.box, kernel, observe_mesh, AveragingRequest{}).vx;
  };
  ref.run = run_direct_sph(scene, ref.particles, options);
  return ref;
}

}  // namespace closurelab
