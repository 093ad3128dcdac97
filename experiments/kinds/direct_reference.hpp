#pragma once
// The direct SPH reference of a scene: run to steady state (the paper's criterion applied to the averaged
// velocity on a column mesh) or to a target time; shared by the validation and reduced-model experiments
// through the persistent reference store (experiments/kinds/reference_store.hpp).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/reference_store.hpp"

namespace closurelab {

struct DirectReference {
  ParticleSystem particles;  // the final state
  SphRunResult run;
};

// One direct run, computed here and now.
DirectReference run_direct_reference(const Scene& scene, const AveragingKernel& kernel, SphRunOptions options,
                                     const TensorMesh2D& observed);

// The mesh whose averaged v_x decides a direct run's steady state: a column of rows of the given spacing for an
// x-invariant scene (core/averaging/averaging.hpp, column_mesh), else a periodic tensor mesh of that spacing.
// ConfigError at `path` (check_observe_mesh) when its node count, computed in double, exceeds an int or its
// averages the memory limit (core/base/memory_limit.hpp).
TensorMesh2D observe_mesh(const Scene& scene, double spacing);
void check_observe_mesh(const Scene& scene, double spacing, const std::string& path);

// What determines a direct reference: the resolved scene, kernel and SPH solver sections of a cell, the row
// spacing of the column mesh whose averaged velocity decides steady state, and the snapshot times.
struct ReferenceRequest {
  json scene, kernel, solver;
  double observe_spacing = 0.0;  // absolute (model length)
  std::vector<double> snapshot_times;
};

// The store key of a request: the sections, the spacing, the times and the engine version
// (core/sph/engine_version.hpp); the solver's progress interval, which changes no result, is left out.
json reference_key(const ReferenceRequest& request);

// The reference from the process-wide store (reference_store()), computed and stored when absent. The run's
// record gains "reference_store": {entry, reused, computed_by}.
StoredReference stored_direct_reference(const ReferenceRequest& request, const Scene& scene,
                                        const AveragingKernel& kernel,
                                        const std::function<void(const std::string&)>& progress);

// The reference a reduced-model cell is scored against, from its resolved `reference` section: a particle file in
// place of the direct run (reference.file at reference.step, read and checked against the scene by
// read_reference_file, reference_profiles.hpp), else the direct SPH run from the store (reference.direct_sph, its
// solver section, `observe_spacing` (absolute) and the snapshot times). One place for every reduced model.
struct CellReference {
  ParticleSystem particles;                 // the final state
  std::vector<ParticleSnapshot> snapshots;  // at the requested times, in order (a direct run only; it may end before some)
  json record;                              // the direct run's record, or the file's
  bool from_file = false;
  // The row's record of the reference: "direct_sph" for a run, "reference_file" for a file.
  void record_into(json& row) const { row[from_file ? "reference_file" : "direct_sph"] = record; }
  // The direct run whose time the speed-up divides; null for a file (no direct run was timed).
  const json* timed_run() const { return from_file ? nullptr : &record; }
};
// None when the cell asks for neither (reference.direct_sph false, no file).
std::optional<CellReference> cell_reference(const json& cfg, const Scene& scene, const AveragingKernel& kernel,
                                            double observe_spacing, const std::vector<double>& snapshot_times,
                                            const std::function<void(const std::string&)>& progress);

}  // namespace closurelab
