#pragma once
// Particle snapshots on disk: HDF5 in the H5Part layout (core/io/h5part.hpp; opens as it is in ParaView's
// H5Part reader and in h5py) and CSV with the header x,y,vx,vy,mass,phase (a snapshot from another code).
// `read_particle_snapshot` picks the reader by the file's extension (.h5part/.h5/.hdf5, or .csv); an HDF5 file
// in PySPH's own output layout (core/io/pysph_output.hpp) is read as PySPH wrote it.
// Every reader refuses a missing or unreadable file, missing columns, arrays of unequal length, non-finite
// values, non-positive masses and negative phases with a ConfigError naming the file (and the line of a CSV).
#include <string>
#include <vector>

#include "core/sph/particles.hpp"

namespace closurelab {

struct ParticleSnapshot {
  double time = 0.0;
  ParticleSystem particles;
  // False when the file carries no held-fixed flags (CSV, or an H5Part file from elsewhere without the
  // `fixed` dataset): particles.fixed is then all 0 and the caller decides (e.g. by the scene's walls).
  bool has_fixed = false;
};

// A CSV file: a header naming at least x, y, vx, vy, mass and phase (any order, each once; other columns ignored;
// an optional `fixed` column of 0/1 is read), then one particle per line. Lines starting with '#' are skipped.
ParticleSnapshot read_particle_csv(const std::string& file);

// The snapshot at `step` of a file (H5Part: the group number N of Step#N, -1 the last; PySPH output and CSV: a single
// step, 0 or -1).
ParticleSnapshot read_particle_snapshot(const std::string& file, int step = -1);

// Checks shared by the readers: equal lengths, finite values, positive masses, phases >= 0. `what` names
// the file in the message.
void check_particles(const ParticleSystem& ps, const std::string& what);

}  // namespace closurelab
