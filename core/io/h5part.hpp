#pragma once
// Particle snapshots in HDF5 with the H5Part layout (Debian's libhdf5, its C API): one group `Step#k` per
// snapshot, k = 0, 1, ..., with the attribute `TimeValue` (double) and one 1D dataset per particle
// quantity: x, y, z (zeros: H5Part readers such as ParaView's want three coordinates), vx, vy (float64),
// mass (float64), phase (int32) and fixed (uint8, 1: held at rest). Readers need x, y, vx, vy and mass;
// phase defaults to 0 and a missing `fixed` leaves ParticleSnapshot::has_fixed false.
// libhdf5 as Debian builds it is not thread-safe: every call here holds one process-wide mutex.
#include <string>
#include <vector>

#include "core/io/particle_snapshot.hpp"

namespace closurelab {

// Writes (replaces) `file` with the snapshots as steps 0, 1, ... Throws std::runtime_error on a write error.
void write_h5part(const std::string& file, const std::vector<ParticleSnapshot>& steps);

// The number of steps in `file` (ConfigError when it is not a readable HDF5 file).
int h5part_step_count(const std::string& file);
// Step `step` (-1: the last). ConfigError naming the file and the dataset on anything missing or malformed.
ParticleSnapshot read_h5part(const std::string& file, int step = -1);
// Every step in order.
std::vector<ParticleSnapshot> read_h5part_all(const std::string& file);

}  // namespace closurelab
