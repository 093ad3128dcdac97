#pragma once
// An independent evaluation of the 2D force-density model's pressure map (core/reduced/force_density_2d.hpp) for
// its tests: the pair force (5.1) with the equation of state, f_a = −Σ_b (P_a/n_a² + P_b/n_b²) F q_ab / m, by a
// plain all-pairs loop over the fluid particles a, with n = n0 + ε δn, and its derivative in ε by a central
// difference. Distances take the minimum image along the box's periodic axes; n0 is the number density of the
// lattice particle `full_stencil` (one whose stencil lies inside the box).
#include <Eigen/Core>
#include <cmath>
#include <cstddef>

#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab::testing {

inline void linearised_pressure_force(const Scene& scene, const ParticleSystem& ps, const Eigen::VectorXd& dn,
                                      std::size_t full_stencil, Eigen::VectorXd& dfx, Eigen::VectorXd& dfy) {
  const SmoothingKernel w = scene.smoothing_kernel();
  const auto image = [](double d, double l, bool periodic) { return periodic ? d - l * std::nearbyint(d / l) : d; };
  const auto q_of = [&](std::size_t a, std::size_t b) {
    return Vec2(image(ps.x[a] - ps.x[b], scene.box.lx, scene.box.periodic_x),
                image(ps.y[a] - ps.y[b], scene.box.ly, scene.box.periodic_y));
  };
  const std::size_t np = ps.size();
  double n0 = w.w(0.0);
  for (std::size_t b = 0; b < np; ++b) {
    const double r = q_of(full_stencil, b).norm();
    if (b != full_stencil && r < w.support()) n0 += w.w(r);
  }
  const double m = scene.particle_mass();
  const auto forces = [&](double eps, Eigen::VectorXd& fx, Eigen::VectorXd& fy) {
    fx = fy = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(np));
    for (std::size_t a = 0; a < np; ++a) {
      if (ps.fixed[a]) continue;
      const double na = n0 + eps * dn[static_cast<Eigen::Index>(a)];
      for (std::size_t b = 0; b < np; ++b) {
        const Vec2 q = q_of(a, b);
        const double r = q.norm();
        if (b == a || r >= w.support()) continue;
        const double nb = n0 + eps * dn[static_cast<Eigen::Index>(b)];
        const Vec2 f = sph_pair_force(scene.pressure(na, m) / (na * na), scene.pressure(nb, m) / (nb * nb), 0.0, na, nb,
                                      w.dw(r) / r, q, Vec2::Zero());
        fx[static_cast<Eigen::Index>(a)] += f.x() / m;
        fy[static_cast<Eigen::Index>(a)] += f.y() / m;
      }
    }
  };
  const double eps = 1e-4 * n0;
  Eigen::VectorXd fxp, fyp, fxm, fym;
  forces(eps, fxp, fyp);
  forces(-eps, fxm, fym);
  dfx = (fxp - fxm) / (2.0 * eps);
  dfy = (fyp - fym) / (2.0 * eps);
}

}  // namespace closurelab::testing
