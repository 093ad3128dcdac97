#pragma once
// Allocation guard: a request for a large block is compared with a limit before it is made, so a run that
// cannot fit is refused with the estimate and the limit (a ConfigError naming what asked) instead of dying
// in the allocator or the OOM killer. Sizes are counted in double (no wrap-around for any size).
#include <cstdint>
#include <string>

namespace closurelab {

// The limit: set_memory_limit_bytes (`run --memory-limit`), else the environment's CLOSURELAB_MEMORY_LIMIT, else
// half of the physical memory (sysconf), or 8 GiB where it cannot be read.
std::uint64_t memory_limit_bytes();
// Where the limit comes from, for messages ("half the physical memory", "--memory-limit", ...).
std::string memory_limit_source();
// 0 restores the default.
void set_memory_limit_bytes(std::uint64_t bytes);
// "8GB", "512 MiB", "1e9", "4096": a byte count (B, kB/MB/GB/TB powers of 1000, KiB/MiB/GiB/TiB of 1024);
// ConfigError(what, ...) when it is not a positive size.
std::uint64_t parse_byte_count(const std::string& text, const std::string& what);

// Throws ConfigError(path, ...) when count * bytes_per_item (computed without overflow) exceeds the limit.
void check_allocation(double count, double bytes_per_item, const std::string& what, const std::string& path = "");

// A direct SPH run of n_x * n_y particles: about kBytesPerParticle each (state, masses and phases ~45 B,
// engine arrays ~60 B, the pair list with its cached geometry ~32 B per pair and ~15-20 pairs per particle
// at h = epsilon' with the quintic support, OpenMP force buffers). Measured: 515 B per particle at one thread
// (max RSS 81 MB for a 384 x 384 lattice against 9 MB for 64 x 64); 700 B leaves room for per-thread buffers.
// Refused with the estimate at validation.
inline constexpr double kBytesPerParticle = 700.0;
void check_particle_memory(long nx, long ny, const std::string& path);

// The 2D force-density model's assembly (core/reduced/force_density_2d.cpp), counted before any of it is made:
// seven dense maps coarse x reconstruction nodes, the two dense forward operators and the two deconvolved
// identity blocks (reconstruction x coarse), and the steady system over the coarse nodes with its LU copy
// ((3 N_c)² twice; N_c² twice for an x-invariant scene, whose x-momentum is solved alone). A lower bound: the
// deconvolvers' own factorisations come on top. Measured: 625 coarse x 1024 reconstruction nodes (cylinder-lattice
// n = 32, eta' = 0.04 L, refinement 0) reached a max RSS of 204 MB, 124 MB above the process at rest; counted 113 MB.
double force_density_2d_bytes(double coarse_nodes, double reconstruction_nodes, bool x_invariant);
void check_force_density_2d_memory(double coarse_nodes, double reconstruction_nodes, bool x_invariant,
                                   const std::string& path);

// The cellular 2D model's coarse mesh of n_x * n_y nodes (core/reduced/meso_solver_2d.cpp): the two dense 1D
// kernel matrices of its averaging operator (at least n_x² + n_y², coarse unknowns; the lattice's are more) and
// about kDoublesPerMesh2DNode fields per node (v̄, ρ̄, F̄, the stresses on both face meshes, the integrator's
// stages). A lower bound, checked before the mesh is made (its counts in double, before any int).
inline constexpr double kDoublesPerMesh2DNode = 16.0;
void check_mesh_2d_memory(double nx, double ny, const std::string& path);

// The experiment matrix's cell limit (the product of the axes, times the explicit cells): set_max_cells
// (`run --max-cells`), else CLOSURELAB_MAX_CELLS, else kDefaultMaxCells. Expanding 10⁶ cells took 4 GB and 38 s.
inline constexpr std::uint64_t kDefaultMaxCells = 100000;
std::uint64_t max_cells();
std::string max_cells_source();
void set_max_cells(std::uint64_t cells);  // 0 restores the default

// "8.0 TB", "512 MB": a byte count for messages.
std::string format_bytes(double bytes);

}  // namespace closurelab
