#pragma once
// Cell-list neighbour search with periodic images: the list of particle pairs closer than a radius.
#include <cstdint>
#include <vector>

#include "core/sph/particles.hpp"

namespace closurelab {

struct PairList {
  std::vector<std::int32_t> i, j;  // each unordered pair once
  std::size_t size() const { return i.size(); }
};

// Pairs (a, b), a != b, among the particles listed in `subset` (indices into `ps`), whose minimum-image
// distance is below `radius`. `keep(a, b)` filters pairs (e.g. drops pairs of two fixed particles).
// The box must hold at least 3 cells of size >= radius along each periodic axis.
template <class Keep>
PairList find_pairs(const ParticleSystem& ps, const std::vector<std::int32_t>& subset, const PeriodicBox& box,
                    double radius, Keep keep);

// Which fixed particles lie within `reach` (minimum image) of some moving particle (1) or not (0), indexed like
// `ps` (moving particles 0): the moving ones binned in cells at least `reach` wide, each fixed particle looking
// into its own cell and the eight around it. Unlike find_pairs it accepts fewer than three cells along a periodic
// axis (some cell is then seen twice, which a yes/no answer does not mind): the narrowest channel strip holds
// only two cells of the engine's reach (support + skin + one spacing).
std::vector<std::uint8_t> fixed_within_reach_of_moving(const ParticleSystem& ps, const PeriodicBox& box, double reach);

// A pair list grouped by its first particle: pairs (i, j), i < j, in rows of one i (j ascending), the rows cut
// into blocks of about `block_pairs` pairs (the unit of the SPH engine's pair passes and of their threads).
struct GroupedPairList {
  PairList pairs;                   // grouped by i
  std::vector<std::int32_t> row_i;  // row r: particle i of pairs [row_begin[r], row_begin[r + 1])
  std::vector<std::uint32_t> row_begin;
  std::vector<std::uint32_t> block_row;  // block b: rows [block_row[b], block_row[b + 1])
  std::size_t longest_block = 0;         // pairs in the largest block
};

// Groups `list` (each pair once, i < j, particle indices below `n_particles`) by a counting sort on i.
GroupedPairList group_by_first_particle(PairList list, std::size_t n_particles, std::size_t block_pairs = 256);

// Orders `subset` by cell (y-major), so particles that interact are close in memory.
void sort_by_cell(const ParticleSystem& ps, std::vector<std::int32_t>& subset, const PeriodicBox& box, double cell);

}  // namespace closurelab

#include "core/sph/neighbour_search_impl.hpp"
