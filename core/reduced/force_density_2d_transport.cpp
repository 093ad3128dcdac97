// The 2D force-density model's transport-velocity linearisation (solver.pair_forces: transport_velocity;
// core/reduced/force_density_2d.hpp): what the assembly in force_density_2d.cpp reads beyond the lattice stencil.
#include <cmath>

#include "core/reduced/force_density_2d_assembly.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab::force_density_detail {

TransportLinearisation transport_linearisation(const Scene& scene, const ParticleSystem& lattice,
                                               const std::vector<int>& site, const std::vector<LatticeOffset>& stencil,
                                               double n0, double p0) {
  TransportLinearisation t;
  const SmoothingKernel w = scene.smoothing_kernel();
  const double m = scene.particle_mass(), rho_rest = m * n0, dx = scene.dx;
  t.vol2_fluid = 1.0 / (n0 * n0);
  t.vol2_wall = dx * dx * dx * dx;  // PySPH: solid.V = 1/dx², never updated
  t.eta_per_mu = rho_rest / scene.rho0;
  t.eps = 0.01 * w.h() * w.h();
  t.rest_volume_term = 2.0 * p0 / (n0 * n0 * n0);
  const std::size_t np = lattice.size();
  t.shepard.resize(np);
  t.hydrostatic.assign(np, 0.0);
  const int lnx = scene.nx, lny = scene.ny;
  for (int j = 0; j < lny; ++j)
    for (int i = 0; i < lnx; ++i) {
      const auto a = static_cast<std::size_t>(site[static_cast<std::size_t>(j * lnx + i)]);
      if (!lattice.fixed[a]) continue;
      double sum_w = 0.0, rx = 0.0, ry = 0.0;
      std::vector<std::pair<int, double>>& out = t.shepard[a];
      for (const LatticeOffset& o : stencil) {
        if (!scene.box.periodic_y && (j + o.dj < 0 || j + o.dj >= lny)) continue;
        const long bi = ((i + o.di) % lnx + lnx) % lnx, bj = ((j + o.dj) % lny + lny) % lny;
        const int f = site[static_cast<std::size_t>(bj * lnx + bi)];
        if (lattice.fixed[static_cast<std::size_t>(f)]) continue;
        const double wf = w.w(std::hypot(o.qx, o.qy));
        if (wf == 0.0) continue;
        sum_w += wf;
        rx += rho_rest * o.qx * wf;  // q = x_w − x_f
        ry += rho_rest * o.qy * wf;
        out.emplace_back(f, wf);
      }
      if (sum_w <= 1e-12) {
        out.clear();
        continue;
      }
      for (auto& e : out) e.second /= sum_w;
      const Vec2 g = scene.body_force ? scene.body_force(lattice.x[a], lattice.y[a])
                                      : Vec2(scene.force_x ? scene.force_x(lattice.y[a]) : 0.0, 0.0);
      t.hydrostatic[a] = (g.x() * rx + g.y() * ry) / sum_w;
    }
  return t;
}

}  // namespace closurelab::force_density_detail
