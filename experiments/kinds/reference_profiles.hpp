#pragma once
// The 1D reduced kind's reference (experiments/kinds/reduced_model.cpp) as profiles at the coarse nodes, from a
// particle state: the direct SPH run's final particles, or a particle snapshot read from a file (reference.file:
// H5Part, PySPH's own HDF5 output or CSV, core/io/particle_snapshot.hpp). Both go through reference_profiles, so
// a file holding the direct run's particles gives the direct run's errors (to the round-off of the particle order).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/params.hpp"
#include "core/io/particle_snapshot.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

struct ReferenceProfiles {
  Eigen::VectorXd averaged;  // v̄_x of the final state at the coarse nodes (2.9)
  json run;                  // the direct run's record (null for a file)
  std::vector<Eigen::VectorXd> snapshots;  // v̄_x at the transient times (direct run only)
  Eigen::VectorXd row_y, row_velocity;     // the final v_x as an x-mean per fluid lattice row
  ParticleSystem particles;                // the final state (the positions oracle probes on it)
};

// The kernel-averaged v_x of `particles` at `nodes` (a column: one x cell over the box) and the x-mean v_x per
// lattice row of the particles not held fixed.
Eigen::VectorXd average_on_nodes(const ParticleSystem& particles, const Scene& scene, const AveragingKernel& kernel,
                                 const Eigen::VectorXd& nodes);
ReferenceProfiles reference_profiles(const ParticleSystem& particles, const Scene& scene,
                                     const AveragingKernel& kernel, const Eigen::VectorXd& nodes);

// The "file" and "step" parameters that the reduced kinds add to their reference section.
ParamSchema reference_file_schema();
// The shared reference section (reduced_sections.hpp) with "file" and "step".
ParamSchema reference_with_file_schema();
// A stored row's parameters from before reference.file existed (its reference section without `file` and `step`):
// it ran against the direct SPH, which is what the defaults (no file, step -1) ask for, so they are filled in
// (ExperimentKind::upgraded_params of the kinds whose reference section has them).
json with_reference_file_defaults(json params);

struct ReferenceFile {
  ParticleSystem particles;  // held-fixed flags from the scene (walls and solids) where the file has none
  json record;               // path, bytes, fnv1a64, layout, step, time, particles
};

// Reads `file` at `step` and checks it against the scene: readable, the scene's particle count, every particle
// inside the box [0, lx) x [0, ly) with a phase the scene has, and the lattice's extent in x and y (a snapshot of
// another box). ConfigError at JSON path `path` (the cell's /reference/file) on any of these. Where the file has
// no held-fixed flags, a particle is held fixed when the scene holds its nearest lattice site (Scene::is_solid:
// walls and solids), as the scene's own lattice is built.
ReferenceFile read_reference_file(const Scene& scene, const std::string& file, int step, const std::string& path);

// The resolve-time checks of a cell (`cell` as given, `out` its resolved sections, errors under `path`): with
// reference.file, no transient t_star (the direct run's history; where the kind has a transient section), no
// reference.solver or observe_spacing_over_eta given (they would be silently unused), direct_sph not false, and the
// file read and checked (read_reference_file); without one, no reference.step.
void check_reference_file(const json& cell, const json& out, const Scene& scene, const std::string& path);

// A row whose reference was read from a file: no direct run was timed, so no speed-up (null, not 0), and a note.
void mark_untimed_reference(json& row);

}  // namespace closurelab
