// The transport-velocity formulation's passes and step in the direct SPH engine (core/sph/transport_velocity.hpp:
// PySPH 1.0b1's TVFScheme, with the generalized wall condition of Adami, Hu & Adams (2012) for fixed particles).
#include <omp.h>

#include <cmath>

#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_pair_passes.hpp"

namespace closurelab {

void SphEngine::prepare_transport_inputs() {
  if (tvx_.empty()) {  // ṽ = v at the first evaluation
    tvx_ = ps_.vx;
    tvy_ = ps_.vy;
  }
  const std::size_t na = active_.size();
  const double rho0 = scene_.rho0;
#pragma omp parallel for num_threads(static_cast <int>(thread_buf_.size())) schedule(static)
  for (std::size_t k = 0; k < na; ++k) {
    const int a = active_[k];
    tvf_input_[a] = tvf_particle(n_[a], ps_.mass[a], pressure(a), mu_[a] / rho0, ps_.vx[a], ps_.vy[a], tvx_[a], tvy_[a]);
  }
}

void SphEngine::apply_transport_wall_condition() {
  if (!transport_walls_) return;
  const std::size_t n = ps_.size();
  if (wall_sum_w_.size() != n) {
    wall_sum_w_.assign(n, 0.0);
    wall_sum_vx_.assign(n, 0.0);
    wall_sum_vy_.assign(n, 0.0);
    wall_sum_p_.assign(n, 0.0);
    wall_sum_rx_.assign(n, 0.0);
    wall_sum_ry_.assign(n, 0.0);
  }
  for (int a : active_)
    if (ps_.fixed[a])
      wall_sum_w_[a] = wall_sum_vx_[a] = wall_sum_vy_[a] = wall_sum_p_[a] = wall_sum_rx_[a] = wall_sum_ry_[a] = 0.0;
  // SetWallVelocity and SolidWallPressureBC's sums over each wall particle's fluid neighbours (one thread: the
  // fluid–wall pairs are a thin band).
  const std::uint8_t* fixed = ps_.fixed.data();
  for (std::size_t p : wall_pairs_) {
    const int i = list_.pairs.i[p], j = list_.pairs.j[p];
    const bool i_wall = fixed[i] != 0;
    const int w = i_wall ? i : j, f = i_wall ? j : i;
    const double xwf = i_wall ? pair_dx_[p] : -pair_dx_[p], ywf = i_wall ? pair_dy_[p] : -pair_dy_[p];  // XIJ
    const double wij = w_.w(std::sqrt(xwf * xwf + ywf * ywf));
    if (wij == 0.0) continue;
    const double rw = tvf_input_[f].rho * wij;
    wall_sum_w_[w] += wij;
    wall_sum_vx_[w] += ps_.vx[f] * wij;
    wall_sum_vy_[w] += ps_.vy[f] * wij;
    wall_sum_p_[w] += tvf_input_[f].p * wij;
    wall_sum_rx_[w] += rw * xwf;  // Σ ρ_f x_wf W, dotted with the body force once per wall particle
    wall_sum_ry_[w] += rw * ywf;
  }
  const double rho0 = scene_.rho0, p0 = rho0 * scene_.sound_speed * scene_.sound_speed;
  const double vol = scene_.dx * scene_.dx, vol2 = vol * vol;  // PySPH: solid.V = 1/dx², never updated
  for (int a : active_) {
    if (!ps_.fixed[a]) continue;
    const double sw = wall_sum_w_[a];
    Vec2 g(0.0, 0.0);  // the body force at the wall particle (its own acceleration is 0: walls are fixed)
    if (scene_.body_force)
      g = scene_.body_force(ps_.x[a], ps_.y[a]);
    else if (scene_.force_x)
      g = Vec2(scene_.force_x(ps_.y[a]), 0.0);
    double ufx = wall_sum_vx_[a], ufy = wall_sum_vy_[a];
    double p = wall_sum_p_[a] + (g.x() * wall_sum_rx_[a] + g.y() * wall_sum_ry_[a]);
    if (sw > 1e-12) ufx /= sw, ufy /= sw;  // SetWallVelocity.post_loop
    if (sw > 1e-14) p /= sw;                // SolidWallPressureBC.post_loop
    const double rho = rho0 * ((p - scene_.background_pressure) / p0 + 1.0);
    // ps_.v of a fixed particle is its prescribed velocity v_w; the wall carries the ghost velocity 2 v_w − ṽ_w.
    tvf_input_[a] = {rho, p, vol2, mu_[a] / rho0 * rho, 2.0 * ps_.vx[a] - ufx, 2.0 * ps_.vy[a] - ufy,
                     0.0, 0.0, 0.0, 0.0};
  }
}

void SphEngine::compute_transport_accelerations() {
  compute_density();
  prepare_transport_inputs();
  apply_transport_wall_condition();
  const std::size_t n = ps_.size(), m = moving_.size();
  const PairBlocks g = blocks();
  const std::size_t nb = list_.block_row.size() - 1;
  const double *F = pair_f_.data(), *qx = pair_dx_.data(), *qy = pair_dy_.data();
  const TvfParticle* in = tvf_input_.data();
  const double* sw = stress_weight_.data();
  const double eps = transport_eps_, pb = background_pressure_;
#pragma omp parallel num_threads(static_cast <int>(thread_buf_.size()))
  {
    const std::size_t t = omp_get_thread_num(), nt = omp_get_num_threads();
    auto& buf = thread_buf_[t];
    std::fill(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(4 * n), 0.0);
    const std::size_t r0 = list_.block_row[nb * t / nt], r1 = list_.block_row[nb * (t + 1) / nt];
    // Fluid–fluid and fluid–wall pairs alike: a wall particle's inputs (apply_transport_wall_condition) make its
    // pairs those of the generalized wall condition.
    if (transport_walls_)
      pair_passes::force_rows_with_background(
          g, r0, r1, F,
          [&](int i, int j, std::size_t p, double& fx, double& fy, double& bx, double& by) {
            tvf_pair_force<true>(in[i], in[j], F[p], qx[p], qy[p], eps, pb, fx, fy, bx, by, sw[i] * sw[j]);
          },
          buf.data());
    else
      pair_passes::force_rows_with_background(
          g, r0, r1, F,
          [&](int i, int j, std::size_t p, double& fx, double& fy, double& bx, double& by) {
            tvf_pair_force(in[i], in[j], F[p], qx[p], qy[p], eps, pb, fx, fy, bx, by);
          },
          buf.data());
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < m; ++k) {
      const int a = moving_[k];
      double fx = 0.0, fy = 0.0, tx = 0.0, ty = 0.0;
      for (std::size_t u = 0; u < nt; ++u) {
        const double* f = thread_buf_[u].data() + 4 * a;
        fx += f[0], fy += f[1], tx += f[2], ty += f[3];
      }
      ax_[a] = fx / ps_.mass[a];
      ay_[a] = fy / ps_.mass[a];
      bx_[a] = tx / ps_.mass[a];
      by_[a] = ty / ps_.mass[a];
      if (scene_.body_force) {  // MomentumEquationPressureGradient.post_loop adds the body force to au only
        const Vec2 b = scene_.body_force(ps_.x[a], ps_.y[a]);
        ax_[a] += b.x();
        ay_[a] += b.y();
      } else {
        ax_[a] += scene_.force_x(ps_.y[a]);
      }
    }
  }
}

void SphEngine::transport_step(double dt) {
  if (!built_) compute_accelerations();
  const std::size_t m = moving_.size();
  const PeriodicBox& box = scene_.box;
  const double dtb2 = 0.5 * dt;
  // TransportVelocityStep.stage1: v += ½Δt a (eq. 14); ṽ = v + ½Δt â (eq. 15); x += Δt ṽ (eq. 16).
#pragma omp parallel for num_threads(static_cast <int>(thread_buf_.size())) schedule(static)
  for (std::size_t k = 0; k < m; ++k) {
    const int a = moving_[k];
    ps_.vx[a] += dtb2 * ax_[a];
    ps_.vy[a] += dtb2 * ay_[a];
    tvx_[a] = ps_.vx[a] + dtb2 * bx_[a];
    tvy_[a] = ps_.vy[a] + dtb2 * by_[a];
    double x = ps_.x[a] + dt * tvx_[a];
    if (box.periodic_x) x -= box.lx * std::floor(x / box.lx);
    double y = ps_.y[a] + dt * tvy_[a];
    if (box.periodic_y) y -= box.ly * std::floor(y / box.ly);
    ps_.x[a] = x;
    ps_.y[a] = y;
  }
  compute_accelerations();
  // stage2: v += ½Δt a (eq. 17).
#pragma omp parallel for num_threads(static_cast <int>(thread_buf_.size())) schedule(static)
  for (std::size_t k = 0; k < m; ++k) {
    const int a = moving_[k];
    ps_.vx[a] += dtb2 * ax_[a];
    ps_.vy[a] += dtb2 * ay_[a];
  }
}

}  // namespace closurelab
