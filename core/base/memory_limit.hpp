#pragma once
// Allocation guard: a request for a large block is compared with a limit before it is made, so a run that
// cannot fit is refused with the estimate and the limit (a ConfigError naming what asked) instead of dying
// in the allocator or the OOM killer.
#include <cstdint>
#include <string>

namespace closurelab {

// Half of the physical memory (sysconf), or 8 GiB where it cannot be read.
std::uint64_t memory_limit_bytes();

// Throws ConfigError(path, ...) when count * bytes_per_item (computed without overflow) exceeds the limit.
void check_allocation(double count, double bytes_per_item, const std::string& what, const std::string& path = "");

// A direct SPH run of n_x * n_y particles: about kBytesPerParticle each (state, masses and phases ~45 B,
// engine arrays ~60 B, the pair list with its cached geometry ~32 B per pair and ~15-20 pairs per particle
// at h = epsilon' with the quintic support, OpenMP force buffers). Measured: 515 B per particle at one thread
// (max RSS 81 MB for a 384 x 384 lattice against 9 MB for 64 x 64); 700 B leaves room for per-thread buffers.
// Refused with the estimate at validation.
inline constexpr double kBytesPerParticle = 700.0;
void check_particle_memory(long nx, long ny, const std::string& path);

// "8.0 TB", "512 MB": a byte count for messages.
std::string format_bytes(double bytes);

}  // namespace closurelab
