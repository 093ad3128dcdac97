#include "core/reduced/averaged_force_map.hpp"

#include <cmath>
#include <map>

#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

// Σ_{a∈members} sign f_a^x ψ(node − q_a) as an affine map of the velocity of `rows` (lattice row → particles).
AveragedForceMap probe(const Scene& strip, ParticleSystem& lattice, const AveragingKernel& kernel,
                       const UniformMesh1D& nodes, const std::vector<std::int32_t>& members, double sign,
                       const std::map<long, std::vector<std::int32_t>>& rows) {
  SphEngine engine(strip, lattice);
  // ψ(node − q_a) on the column at x = 0, the periodic images in x summed.
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(nodes.count, static_cast<Eigen::Index>(members.size()));
  const double r = kernel.support_radius();
  const UniformMesh1D x_axis{0.0, strip.box.lx, 1, true, strip.box.lx};
  for (std::size_t m = 0; m < members.size(); ++m) {
    const int a = members[m];
    double wx = 0.0;
    for_nodes_within(x_axis, lattice.x[a], r, [&](int, double d) { wx += kernel.factor(d); });
    for_nodes_within(nodes, lattice.y[a], r, [&](int n, double d) {
      weights(n, static_cast<Eigen::Index>(m)) += wx * kernel.factor(d);
    });
  }
  const auto averaged = [&]() {
    std::vector<double> net(lattice.size(), 0.0);
    for (const PairForce& p : engine.pair_forces()) {
      net[p.j] += p.f.x();
      net[p.k] -= p.f.x();
    }
    Eigen::VectorXd f(static_cast<Eigen::Index>(members.size()));
    for (std::size_t m = 0; m < members.size(); ++m) f[static_cast<Eigen::Index>(m)] = sign * net[members[m]];
    return Eigen::VectorXd(weights * f);
  };
  AveragedForceMap out;
  out.offset = averaged();
  out.map = Eigen::MatrixXd::Zero(nodes.count, static_cast<Eigen::Index>(rows.size()));
  Eigen::Index col = 0;
  for (const auto& [row, ids] : rows) {
    for (int a : ids) lattice.vx[a] = 1.0;
    out.map.col(col++) = averaged() - out.offset;
    for (int a : ids) lattice.vx[a] = 0.0;
    out.rows.emplace_back(0.0, lattice.y[ids.front()]);
  }
  return out;
}

long row_of(double y, double dx) { return std::lround(y / dx - 0.5); }

}  // namespace

AveragedForceMap wall_constraint_force_map(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes) {
  const Scene strip = scene.narrowest_strip();
  ParticleSystem lattice = strip.make_particles();
  const double reach = SmoothingKernel::from_name(scene.smoothing_kernel, scene.h).support();
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
  return probe(strip, lattice, kernel, nodes, walls, -1.0, rows);
}

AveragedForceMap fluid_force_density_map(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes) {
  const Scene strip = scene.narrowest_strip();
  ParticleSystem lattice = strip.make_particles();
  std::vector<std::int32_t> fluid;
  std::map<long, std::vector<std::int32_t>> rows;
  for (std::size_t a = 0; a < lattice.size(); ++a)
    if (!lattice.fixed[a]) {
      fluid.push_back(static_cast<std::int32_t>(a));
      rows[row_of(lattice.y[a], scene.dx)].push_back(static_cast<std::int32_t>(a));
    }
  return probe(strip, lattice, kernel, nodes, fluid, 1.0, rows);
}

}  // namespace closurelab
