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

// One `Step#N` group of a file. Files from other codes often number their groups by the time step they were
// written at (Step#0, Step#10, Step#20, ...) or start at Step#1, so a step is found by its name, never by
// counting from Step#0.
struct H5PartStep {
  long long number = 0;  // N of Step#N
  std::string group;     // "Step#N" as in the file
  bool has_time = false;
  double time = 0.0;     // its TimeValue attribute, when it has one
};

// The Step#N groups that exist, by increasing N (ConfigError when the file is not readable HDF5, or when two
// names give one N, e.g. Step#7 and Step#07).
std::vector<H5PartStep> h5part_steps(const std::string& file);
// The number of Step#N groups in `file`.
int h5part_step_count(const std::string& file);

// How a step is picked: by its group number N, by its place in the list above (0-based), or by its TimeValue.
enum class H5PartStepBy { number, index, time };
// The group number of the step picked by `value` (a number or an index; -1: the last) or by `time` (the one step
// whose TimeValue equals it to 1e-9 relative). ConfigError, listing the steps there are, when none or several
// fit.
long long h5part_select_step(const std::string& file, H5PartStepBy by, long long value, double time = 0.0);

// The step of group number `step` (Step#step; -1: the last group). ConfigError naming the file and the dataset
// on anything missing or malformed, and listing the steps there are when Step#step is not among them.
ParticleSnapshot read_h5part(const std::string& file, long long step = -1);
// Every step, by increasing group number.
std::vector<ParticleSnapshot> read_h5part_all(const std::string& file);

}  // namespace closurelab
