#include "experiments/kinds/direct_reference.hpp"

#include <algorithm>
#include <cmath>

#include "core/averaging/averaging.hpp"
#include "core/sph/engine_version.hpp"

namespace closurelab {

DirectReference run_direct_reference(const Scene& scene, const AveragingKernel& kernel, SphRunOptions options,
                                     const TensorMesh2D& observed) {
  DirectReference ref{scene.make_particles(), {}};
  options.observable = [&](const ParticleSystem& p) {
    return average_particles(p, scene.box, kernel, observed, AveragingRequest{}).vx;
  };
  ref.run = run_direct_sph(scene, ref.particles, options);
  return ref;
}

TensorMesh2D observe_mesh(const Scene& scene, double spacing) {
  if (scene.x_invariant) return column_mesh(scene.box, spacing);
  const auto axis = [spacing](double length, bool periodic) {
    return UniformMesh1D::cell_centred(0.0, length, std::max(1, static_cast<int>(std::lround(length / spacing))), periodic);
  };
  return {axis(scene.box.lx, scene.box.periodic_x), axis(scene.box.ly, scene.box.periodic_y)};
}

json reference_key(const ReferenceRequest& r) {
  json solver = r.solver;
  solver.erase("progress_seconds");
  return {{"kind", "direct_sph"},
          {"engine_version", sph_engine_version},
          {"scene", r.scene},
          {"kernel", r.kernel},
          {"solver", solver},
          {"observe_spacing", r.observe_spacing},
          {"snapshot_times", r.snapshot_times}};
}

StoredReference stored_direct_reference(const ReferenceRequest& request, const Scene& scene,
                                        const AveragingKernel& kernel,
                                        const std::function<void(const std::string&)>& progress) {
  StoredReference ref = reference_store().get_or_compute(reference_key(request), [&] {
    StoredReference computed;
    SphRunOptions opt = sph_run_options_from(request.solver);
    opt.progress = progress;
    opt.snapshot_times = request.snapshot_times;
    opt.on_snapshot = [&computed](double t, const ParticleSystem& p) { computed.snapshots.push_back({t, p, true}); };
    DirectReference d = run_direct_reference(scene, kernel, opt, observe_mesh(scene, request.observe_spacing));
    computed.particles = std::move(d.particles);
    computed.run = d.run.to_json();
    return computed;
  });
  ref.run["reference_store"] = ref.store;
  return ref;
}

}  // namespace closurelab
