#pragma once
#include <memory>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {
// "snapshot_closure": a particle snapshot from a file (H5Part or CSV, core/io/particle_snapshot.hpp; e.g. a
// larger SPH run of another code) averaged on a coarse mesh, its averaged velocity deconvolved by a
// registered deconvolver, and the closure's interaction stress (2.13) under the reconstructed velocities
// compared with the snapshot's own exact (2.13) stress, at the snapshot's particle positions.
std::unique_ptr<ExperimentKind> make_snapshot_closure_experiment();
}  // namespace closurelab
