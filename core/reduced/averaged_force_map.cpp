#include "core/reduced/averaged_force_map.hpp"

#include <cmath>
#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <unordered_map>

#include "core/base/errors.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

// Σ_{a∈members} sign f_a^x ψ(node − q_a) as an affine map of the velocity of `rows` (lattice row → particles).
// Two pair sweeps: at rest (the offset: the pressure part) and with every fluid particle at v_x = its row's
// index + 1 (distinct per row); a pair's x-force is affine in v_j − v_k, so the second sweep gives each pair's
// coefficient c_jk wherever v_j ≠ v_k (pairs within one row never differ in an x-invariant field). The column
// of row r then collects ±c_jk (w_j − w_k) over the pairs with an end in r, w the members' signed weights.
// x_weight(a): the x-factor of member a's weight (per unit length in x); row_y(row, first particle): the row's
// sample point.
AveragedForceMap probe(const Scene& strip, ParticleSystem& lattice, const AveragingKernel& kernel,
                       const UniformMesh1D& nodes, const std::vector<std::int32_t>& members, double sign,
                       const std::map<long, std::vector<std::int32_t>>& rows, const std::function<double(int)>& x_weight,
                       const std::function<double(long, int)>& row_y) {
  SphEngine engine(strip, lattice);
  // ψ(node − q_a) for the members (signed), its x-factor per unit length.
  std::vector<std::vector<std::pair<int, double>>> weight(lattice.size());
  const double r = kernel.support_radius();
  for (int a : members) {
    const double wx = x_weight(a);
    for_nodes_within(nodes, lattice.y[a], r, [&](int n, double d) { weight[a].emplace_back(n, sign * wx * kernel.factor(d)); });
  }
  std::vector<int> column(lattice.size(), -1);  // the map column of each fluid particle's row
  AveragedForceMap out;
  for (const auto& [row, ids] : rows) {
    for (int a : ids) column[a] = static_cast<int>(out.rows.size());
    out.rows.emplace_back(0.0, row_y(row, ids.front()));
  }
  const std::vector<PairForce> rest = engine.pair_forces();
  out.offset = Eigen::VectorXd::Zero(nodes.count);
  for (const PairForce& p : rest) {
    for (const auto& [n, w] : weight[p.j]) out.offset[n] += w * p.f.x();
    for (const auto& [n, w] : weight[p.k]) out.offset[n] -= w * p.f.x();
  }
  for (std::size_t a = 0; a < lattice.size(); ++a)
    if (column[a] >= 0) lattice.vx[a] = column[a] + 1.0;
  const std::vector<PairForce> moving = engine.pair_forces();
  for (std::size_t a = 0; a < lattice.size(); ++a) lattice.vx[a] = 0.0;
  if (moving.size() != rest.size()) throw NumericalError("averaged force map: the pair list changed between sweeps");
  out.map = Eigen::MatrixXd::Zero(nodes.count, static_cast<Eigen::Index>(out.rows.size()));
  for (std::size_t p = 0; p < rest.size(); ++p) {
    const int j = rest[p].j, k = rest[p].k;
    if (moving[p].j != j || moving[p].k != k) throw NumericalError("averaged force map: the pair order changed");
    const double vj = column[j] >= 0 ? column[j] + 1.0 : 0.0, vk = column[k] >= 0 ? column[k] + 1.0 : 0.0;
    if (vj == vk) continue;
    const double c = (moving[p].f.x() - rest[p].f.x()) / (vj - vk);  // f_jk^x = rest + c (v_j − v_k)
    const auto add = [&](int col, double s) {  // ∂/∂V_col of the pair's contribution, s = ∂(v_j − v_k)/∂V_col
      for (const auto& [n, w] : weight[j]) out.map(n, col) += s * c * w;
      for (const auto& [n, w] : weight[k]) out.map(n, col) -= s * c * w;
    };
    if (column[j] >= 0) add(column[j], 1.0);
    if (column[k] >= 0) add(column[k], -1.0);
  }
  return out;
}

long row_of(double y, double dx) { return std::lround(y / dx - 0.5); }

// The particles not held fixed, and each one's nearest lattice row.
void fluid_rows(const ParticleSystem& ps, double dx, std::vector<std::int32_t>& fluid,
                std::map<long, std::vector<std::int32_t>>& rows) {
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) {
      fluid.push_back(static_cast<std::int32_t>(a));
      rows[row_of(ps.y[a], dx)].push_back(static_cast<std::int32_t>(a));
    }
}

// On the narrowest strip's lattice: the column at x = 0 with the strip's periodic images in x summed (per unit
// length: the strip's rows are uniform in x), each row sampled at its particles' y. Remembered per x (the strip has
// few columns and many images per particle when it is narrower than the window): the same bits as evaluated afresh.
std::function<double(int)> strip_column_weight(const Scene& strip, const ParticleSystem& lattice,
                                               const AveragingKernel& kernel) {
  auto remembered = std::make_shared<std::unordered_map<double, double>>();
  return [&strip, &lattice, &kernel, remembered](int a) {
    if (const auto it = remembered->find(lattice.x[a]); it != remembered->end()) return it->second;
    const UniformMesh1D x_axis{0.0, strip.box.lx, 1, true, strip.box.lx};
    double wx = 0.0;
    for_nodes_within(x_axis, lattice.x[a], kernel.support_radius(), [&](int, double d) { wx += kernel.factor(d); });
    (*remembered)[lattice.x[a]] = wx;
    return wx;
  };
}
std::function<double(long, int)> lattice_row_y(const ParticleSystem& lattice) {
  return [&lattice](long, int first) { return lattice.y[first]; };
}

}  // namespace

AveragedForceMap wall_constraint_force_map(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes) {
  const Scene strip = scene.narrowest_strip();
  ParticleSystem lattice = strip.make_particles();
  const double reach = scene.smoothing_kernel().support();
  std::vector<std::int32_t> walls;
  std::map<long, std::vector<std::int32_t>> rows;  // fluid rows within reach of a wall
  for (std::size_t a = 0; a < lattice.size(); ++a) {
    const double y = lattice.y[a];
    if (lattice.fixed[a]) {
      if (y > scene.wall_lo - reach && y < scene.wall_hi + reach) walls.push_back(static_cast<std::int32_t>(a));
    } else if (y < scene.wall_lo + reach || y > scene.wall_hi - reach) {
      rows[row_of(y, scene.dx)].push_back(static_cast<std::int32_t>(a));
    }
  }
  return probe(strip, lattice, kernel, nodes, walls, -1.0, rows, strip_column_weight(strip, lattice, kernel),
               lattice_row_y(lattice));
}

AveragedForceMap fluid_force_density_map(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes) {
  const Scene strip = scene.narrowest_strip();
  ParticleSystem lattice = strip.make_particles();
  std::vector<std::int32_t> fluid;
  std::map<long, std::vector<std::int32_t>> rows;
  fluid_rows(lattice, scene.dx, fluid, rows);
  return probe(strip, lattice, kernel, nodes, fluid, 1.0, rows, strip_column_weight(strip, lattice, kernel),
               lattice_row_y(lattice));
}

AveragedForceMap fluid_force_density_map_at(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes,
                                            const ParticleSystem& positions) {
  if (!scene.x_invariant) throw std::logic_error("fluid_force_density_map_at: the scene is not x-invariant");
  if (positions.size() != scene.make_particles().size())
    throw ConfigError("/oracle/positions", "the particle state does not hold the scene's particles");
  ParticleSystem at = positions;  // the positions only: at rest for the probe
  std::fill(at.vx.begin(), at.vx.end(), 0.0);
  std::fill(at.vy.begin(), at.vy.end(), 0.0);
  std::vector<std::int32_t> fluid;
  std::map<long, std::vector<std::int32_t>> rows;
  fluid_rows(at, scene.dx, fluid, rows);
  // The x-average over the box (∫φ = 1): exact for any x-distribution of the particles.
  const double per_length = 1.0 / scene.box.lx;
  return probe(scene, at, kernel, nodes, fluid, 1.0, rows, [per_length](int) { return per_length; },
               [&scene](long row, int) { return (static_cast<double>(row) + 0.5) * scene.dx; });
}

}  // namespace closurelab
