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

// Orders `subset` by cell (y-major), so particles that interact are close in memory.
void sort_by_cell(const ParticleSystem& ps, std::vector<std::int32_t>& subset, const PeriodicBox& box, double cell);

}  // namespace closurelab

#include "core/sph/neighbour_search_impl.hpp"
