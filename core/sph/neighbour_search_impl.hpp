#pragma once
// Template implementation of find_pairs (included by neighbour_search.hpp).
#include <algorithm>
#include <cmath>

#include "core/base/errors.hpp"

namespace closurelab {

namespace detail {

struct CellGrid {
  double x0, y0, cx, cy;
  int nx, ny;
  bool px, py;
  int cell_x(double x) const { return std::clamp(static_cast<int>(std::floor((x - x0) / cx)), 0, nx - 1); }
  int cell_y(double y) const { return std::clamp(static_cast<int>(std::floor((y - y0) / cy)), 0, ny - 1); }
};

CellGrid make_cell_grid(const ParticleSystem& ps, const std::vector<std::int32_t>& subset, const PeriodicBox& box,
                        double radius);

}  // namespace detail

template <class Keep>
PairList find_pairs(const ParticleSystem& ps, const std::vector<std::int32_t>& subset, const PeriodicBox& box,
                    double radius, Keep keep) {
  const detail::CellGrid g = detail::make_cell_grid(ps, subset, box, radius);
  const int ncell = g.nx * g.ny;
  std::vector<int> start(ncell + 1, 0), order(subset.size());
  std::vector<int> cell_of(subset.size());
  for (std::size_t k = 0; k < subset.size(); ++k) {
    const int a = subset[k];
    cell_of[k] = g.cell_y(ps.y[a]) * g.nx + g.cell_x(ps.x[a]);
    ++start[cell_of[k] + 1];
  }
  for (int c = 0; c < ncell; ++c) start[c + 1] += start[c];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < subset.size(); ++k) order[fill[cell_of[k]]++] = static_cast<int>(k);

  PairList out;
  const double r2 = radius * radius;
  out.i.reserve(subset.size() * 16);
  out.j.reserve(subset.size() * 16);
  for (int cy = 0; cy < g.ny; ++cy) {
    for (int cx = 0; cx < g.nx; ++cx) {
      const int c = cy * g.nx + cx;
      // Half of the 3x3 neighbourhood (self, E, NW, N, NE) so that each pair is found once.
      static const int offs[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
      for (const auto& o : offs) {
        int nxc = cx + o[0], nyc = cy + o[1];
        if (nxc < 0 || nxc >= g.nx) {
          if (!g.px) continue;
          nxc = (nxc + g.nx) % g.nx;
        }
        if (nyc < 0 || nyc >= g.ny) {
          if (!g.py) continue;
          nyc = (nyc + g.ny) % g.ny;
        }
        const int d = nyc * g.nx + nxc;
        for (int p = start[c]; p < start[c + 1]; ++p) {
          const int a = subset[order[p]];
          for (int q = (d == c ? p + 1 : start[d]); q < start[d + 1]; ++q) {
            const int b = subset[order[q]];
            const double dx = box.wrap_dx(ps.x[a] - ps.x[b]);
            const double dy = box.wrap_dy(ps.y[a] - ps.y[b]);
            if (dx * dx + dy * dy < r2 && keep(a, b)) {
              out.i.push_back(std::min(a, b));
              out.j.push_back(std::max(a, b));
            }
          }
        }
      }
    }
  }
  return out;
}

}  // namespace closurelab
