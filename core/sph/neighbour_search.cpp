#include "core/sph/neighbour_search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace closurelab {

namespace detail {

CellGrid make_cell_grid(const ParticleSystem& ps, const std::vector<std::int32_t>& subset, const PeriodicBox& box,
                        double radius) {
  CellGrid g{};
  g.px = box.periodic_x;
  g.py = box.periodic_y;
  double xmin = 0.0, xmax = box.lx, ymin = 0.0, ymax = box.ly;
  if (!g.px || !g.py) {
    double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
    for (int a : subset) {
      lo_x = std::min(lo_x, ps.x[a]);
      hi_x = std::max(hi_x, ps.x[a]);
      lo_y = std::min(lo_y, ps.y[a]);
      hi_y = std::max(hi_y, ps.y[a]);
    }
    if (!g.px) xmin = lo_x, xmax = hi_x + 1e-12;
    if (!g.py) ymin = lo_y, ymax = hi_y + 1e-12;
  }
  auto axis = [radius](double lo, double hi, bool periodic, const char* name, double& origin, double& size, int& n) {
    n = std::max(1, static_cast<int>(std::floor((hi - lo) / radius)));
    if (periodic && n < 3)
      throw ConfigError(
          "", std::string("periodic ") + name + "-extent holds fewer than 3 interaction radii; widen the domain");
    origin = lo;
    size = (hi - lo) / n;
    if (!(size > 0)) size = radius, n = 1;
  };
  axis(xmin, xmax, g.px, "x", g.x0, g.cx, g.nx);
  axis(ymin, ymax, g.py, "y", g.y0, g.cy, g.ny);
  return g;
}

}  // namespace detail

void sort_by_cell(const ParticleSystem& ps, std::vector<std::int32_t>& subset, const PeriodicBox& box, double cell) {
  const detail::CellGrid g = detail::make_cell_grid(ps, subset, box, cell);
  std::vector<std::int64_t> key(ps.size(), 0);
  for (int a : subset) key[a] = static_cast<std::int64_t>(g.cell_y(ps.y[a])) * g.nx + g.cell_x(ps.x[a]);
  std::stable_sort(subset.begin(), subset.end(), [&](int a, int b) { return key[a] < key[b]; });
}

GroupedPairList group_by_first_particle(PairList list, std::size_t n_particles, std::size_t block_pairs) {
  const std::size_t np = list.size(), n = n_particles;
  std::vector<std::uint32_t> begin(n + 1, 0);
  for (std::size_t p = 0; p < np; ++p) ++begin[list.i[p] + 1];
  for (std::size_t a = 0; a < n; ++a) begin[a + 1] += begin[a];
  GroupedPairList g;
  g.pairs.i.resize(np);
  g.pairs.j.resize(np);
  std::vector<std::uint32_t> next(begin.begin(), begin.end() - 1);
  for (std::size_t p = 0; p < np; ++p) {
    const std::uint32_t q = next[list.i[p]]++;
    g.pairs.i[q] = list.i[p];
    g.pairs.j[q] = list.j[p];
  }
  g.block_row.assign(1, 0);
  std::size_t block_start = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (begin[a + 1] == begin[a]) continue;
    std::sort(g.pairs.j.begin() + begin[a], g.pairs.j.begin() + begin[a + 1]);
    if (begin[a] - block_start >= block_pairs) {
      g.block_row.push_back(static_cast<std::uint32_t>(g.row_i.size()));
      g.longest_block = std::max<std::size_t>(g.longest_block, begin[a] - block_start);
      block_start = begin[a];
    }
    g.row_i.push_back(static_cast<std::int32_t>(a));
    g.row_begin.push_back(begin[a]);
  }
  g.row_begin.push_back(static_cast<std::uint32_t>(np));
  if (!g.row_i.empty()) g.block_row.push_back(static_cast<std::uint32_t>(g.row_i.size()));
  g.longest_block = std::max<std::size_t>(g.longest_block, np - block_start);
  return g;
}

std::vector<std::uint8_t> fixed_within_reach_of_moving(const ParticleSystem& ps, const PeriodicBox& box, double reach) {
  const std::size_t n = ps.size();
  std::vector<std::uint8_t> near(n, 0);
  if (n == 0) return near;
  struct Axis {
    double origin = 0.0, size = 1.0;
    int cells = 1;
    bool periodic = false;
    int cell(double v) const { return std::clamp(static_cast<int>(std::floor((v - origin) / size)), 0, cells - 1); }
  };
  const auto make_axis = [reach](const std::vector<double>& v, double length, bool periodic) {
    Axis ax;
    ax.periodic = periodic;
    double lo = 0.0, hi = length;
    if (!periodic) lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
    ax.origin = lo;
    ax.cells = std::max(1, static_cast<int>(std::floor((hi - lo) / reach)));
    ax.size = hi > lo ? (hi - lo) / ax.cells : reach;
    return ax;
  };
  const Axis gx = make_axis(ps.x, box.lx, box.periodic_x), gy = make_axis(ps.y, box.ly, box.periodic_y);
  std::vector<std::vector<std::int32_t>> cell(static_cast<std::size_t>(gx.cells) * gy.cells);
  for (std::size_t a = 0; a < n; ++a)
    if (!ps.fixed[a]) cell[static_cast<std::size_t>(gy.cell(ps.y[a])) * gx.cells + gx.cell(ps.x[a])].push_back(a);
  const double reach2 = reach * reach;
  for (std::size_t a = 0; a < n; ++a) {
    if (!ps.fixed[a]) continue;
    const int cx = gx.cell(ps.x[a]), cy = gy.cell(ps.y[a]);
    for (int oy = -1; oy <= 1 && !near[a]; ++oy)
      for (int ox = -1; ox <= 1 && !near[a]; ++ox) {
        int ix = cx + ox, iy = cy + oy;
        if (gx.periodic) ix = (ix + gx.cells) % gx.cells;
        if (gy.periodic) iy = (iy + gy.cells) % gy.cells;
        if (ix < 0 || ix >= gx.cells || iy < 0 || iy >= gy.cells) continue;
        for (const std::int32_t b : cell[static_cast<std::size_t>(iy) * gx.cells + ix]) {
          const double dx = box.wrap_dx(ps.x[a] - ps.x[b]), dy = box.wrap_dy(ps.y[a] - ps.y[b]);
          if (dx * dx + dy * dy <= reach2) {
            near[a] = 1;
            break;
          }
        }
      }
  }
  return near;
}

}  // namespace closurelab
