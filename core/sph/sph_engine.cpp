#include "core/sph/sph_engine.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/base/errors.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab {

SphEngine::SphEngine(const Scene& scene, ParticleSystem& particles)
    : scene_(scene), ps_(particles), w_(scene.smoothing_kernel()) {
  skin_ = 0.5 * scene.dx;
  mass_ = scene.particle_mass();
  const std::size_t n = ps_.size();
  const double reach = w_.support() + skin_ + scene.dx;
  std::vector<std::int32_t> walls;
  for (std::size_t a = 0; a < n; ++a) {
    if (!ps_.fixed[a]) {
      moving_.push_back(static_cast<std::int32_t>(a));
      active_.push_back(static_cast<std::int32_t>(a));
      continue;
    }
    walls.push_back(static_cast<std::int32_t>(a));
    const double dist = ps_.y[a] < scene.wall_lo ? scene.wall_lo - ps_.y[a] : ps_.y[a] - scene.wall_hi;
    if (!scene.has_walls || dist <= reach) active_.push_back(static_cast<std::int32_t>(a));
  }
  sort_by_cell(ps_, active_, scene_.box, w_.support() + skin_);
  n_static_.assign(n, 0.0);
  if (!walls.empty()) {
    const PairList ww = find_pairs(ps_, walls, scene_.box, w_.support(), [](int, int) { return true; });
    for (int a : walls) n_static_[a] = w_.w(0.0);
    for (std::size_t p = 0; p < ww.size(); ++p) {
      const int a = ww.i[p], b = ww.j[p];
      const double r = std::hypot(scene_.box.wrap_dx(ps_.x[a] - ps_.x[b]), scene_.box.wrap_dy(ps_.y[a] - ps_.y[b]));
      n_static_[a] += w_.w(r);
      n_static_[b] += w_.w(r);
    }
  }
  n_.assign(n, 0.0);
  ax_.assign(n, 0.0);
  ay_.assign(n, 0.0);
  mu_.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    const int ph = ps_.phase[a];
    if (ph < 0 || ph >= static_cast<int>(scene.phase_viscosity.size()))
      throw ConfigError("", "particle phase " + std::to_string(ph) + " has no viscosity");
    mu_[a] = scene.phase_viscosity[ph];
  }
  unlike_excess_ = scene.unlike_pair_excess_over_n2();
  thread_buf_.resize(omp_get_max_threads());
  // The ghost-velocity wall multiplies the viscous coupling of a fluid–wall pair by β <= 1 + d_wall/d_fluid;
  // with the wall between lattice rows, d_fluid >= ε'/2 and d_wall < support.
  viscous_stiffening_ = scene.wall_model == WallModel::ghost_velocity
                            ? std::min(scene.ghost_beta_max, 1.0 + w_.support() / (0.5 * scene.dx))
                            : 1.0;
}

void SphEngine::rebuild_pairs_if_needed() {
  if (built_) {
    const double limit2 = 0.25 * skin_ * skin_;
    bool need = false;
    for (int a : moving_) {
      const double dx = scene_.box.wrap_dx(ps_.x[a] - x_built_[a]), dy = scene_.box.wrap_dy(ps_.y[a] - y_built_[a]);
      if (dx * dx + dy * dy > limit2) {
        need = true;
        break;
      }
    }
    if (!need) return;
  }
  const auto& fixed = ps_.fixed;
  pairs_ = find_pairs(ps_, active_, scene_.box, w_.support() + skin_,
                      [&fixed](int a, int b) { return !(fixed[a] && fixed[b]); });
  x_built_ = ps_.x;
  y_built_ = ps_.y;
  pair_dx_.resize(pairs_.size());
  pair_dy_.resize(pairs_.size());
  pair_f_.resize(pairs_.size());
  built_ = true;
  ++list_rebuilds_;
}

void SphEngine::compute_density() {
  rebuild_pairs_if_needed();
  const double w0 = w_.w(0.0), rs2 = w_.support() * w_.support();
  for (int a : active_) n_[a] = ps_.fixed[a] ? n_static_[a] : w0;
  const std::size_t np = pairs_.size(), n = ps_.size();
  const int nthreads = static_cast<int>(thread_buf_.size());
  for (auto& b : thread_buf_) b.assign(n, 0.0);  // all of them: the team may have fewer threads
#pragma omp parallel num_threads(nthreads)
  {
    auto& buf = thread_buf_[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::size_t p = 0; p < np; ++p) {
      const int i = pairs_.i[p], j = pairs_.j[p];
      const double dx = scene_.box.wrap_dx(ps_.x[i] - ps_.x[j]);
      const double dy = scene_.box.wrap_dy(ps_.y[i] - ps_.y[j]);
      const double r2 = dx * dx + dy * dy;
      pair_dx_[p] = dx;
      pair_dy_[p] = dy;
      if (r2 >= rs2) {
        pair_f_[p] = 0.0;
        continue;
      }
      const double r = std::sqrt(r2);
      const double wv = w_.w(r);
      pair_f_[p] = w_.dw(r) / r;
      buf[i] += wv;
      buf[j] += wv;
    }
  }
  for (const auto& buf : thread_buf_)
    for (int a : active_) n_[a] += buf[a];
  pair_evaluations_ += static_cast<std::int64_t>(np);
}

double SphEngine::pressure(std::int32_t a) const { return scene_.pressure(n_[a], ps_.mass[a]); }

Vec2 SphEngine::pair_force(std::size_t p, double p_over_n2_i, double p_over_n2_j) const {
  const int i = pairs_.i[p], j = pairs_.j[p];
  if (ps_.phase[i] != ps_.phase[j]) {  // unlike pair: its k_ij in both pressures of (5.1) with (7.1)
    p_over_n2_i += unlike_excess_;
    p_over_n2_j += unlike_excess_;
  }
  const double mu_ij = pair_viscosity(mu_[i], mu_[j], scene_.pair_viscosity_mean);
  return sph_pair_force(p_over_n2_i, p_over_n2_j, mu_ij, n_[i], n_[j], pair_f_[p], Vec2(pair_dx_[p], pair_dy_[p]),
                        relative_velocity(i, j));
}

Vec2 SphEngine::relative_velocity(std::int32_t a, std::int32_t b) const {
  const bool fa = ps_.fixed[a], fb = ps_.fixed[b];
  if (scene_.wall_model == WallModel::zero_velocity || fa == fb)
    return {ps_.vx[a] - ps_.vx[b], ps_.vy[a] - ps_.vy[b]};
  // Ghost velocity: the wall particle moves with −(d_wall / d_fluid) v_fluid, so that the velocity
  // continued across the wall surface vanishes on it.
  const int f = fa ? b : a, w = fa ? a : b;
  const bool lower = ps_.y[w] < scene_.wall_lo;
  const double d_wall = lower ? scene_.wall_lo - ps_.y[w] : ps_.y[w] - scene_.wall_hi;
  const double d_fluid = std::max(lower ? ps_.y[f] - scene_.wall_lo : scene_.wall_hi - ps_.y[f], 1e-3 * scene_.dx);
  const double beta = std::min(scene_.ghost_beta_max, 1.0 + d_wall / d_fluid);
  const double sign = fa ? -1.0 : 1.0;
  return {sign * beta * ps_.vx[f], sign * beta * ps_.vy[f]};
}

void SphEngine::compute_accelerations() {
  compute_density();
  const std::size_t np = pairs_.size(), n = ps_.size();
  std::vector<double> p_over_n2(n, 0.0);
  for (int a : active_) p_over_n2[a] = pressure(a) / (n_[a] * n_[a]);
  const int nthreads = static_cast<int>(thread_buf_.size());
  for (auto& b : thread_buf_) b.assign(2 * n, 0.0);
#pragma omp parallel num_threads(nthreads)
  {
    auto& buf = thread_buf_[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::size_t p = 0; p < np; ++p) {
      const double F = pair_f_[p];
      if (F == 0.0) continue;
      const int i = pairs_.i[p], j = pairs_.j[p];
      const Vec2 f = pair_force(p, p_over_n2[i], p_over_n2[j]);
      buf[i] += f.x();
      buf[n + i] += f.y();
      buf[j] -= f.x();
      buf[n + j] -= f.y();
    }
  }
  for (int a : moving_) {
    double fx = 0.0, fy = 0.0;
    for (const auto& buf : thread_buf_) fx += buf[a], fy += buf[n + a];
    ax_[a] = fx / ps_.mass[a];
    ay_[a] = fy / ps_.mass[a];
    if (scene_.body_force) {
      const Vec2 b = scene_.body_force(ps_.x[a], ps_.y[a]);
      ax_[a] += b.x();
      ay_[a] += b.y();
    } else {
      ax_[a] += scene_.force_x(ps_.y[a]);
    }
  }
}

void SphEngine::step(double dt) {
  if (!built_) compute_accelerations();
  const std::size_t m = moving_.size();
  std::vector<double> vhx(m), vhy(m);
  for (std::size_t k = 0; k < m; ++k) {
    const int a = moving_[k];
    vhx[k] = ps_.vx[a] + 0.5 * dt * ax_[a];
    vhy[k] = ps_.vy[a] + 0.5 * dt * ay_[a];
    double x = ps_.x[a] + dt * vhx[k];
    if (scene_.box.periodic_x) x -= scene_.box.lx * std::floor(x / scene_.box.lx);
    double y = ps_.y[a] + dt * vhy[k];
    if (scene_.box.periodic_y) y -= scene_.box.ly * std::floor(y / scene_.box.ly);
    ps_.x[a] = x;
    ps_.y[a] = y;
    ps_.vx[a] = vhx[k] + 0.5 * dt * ax_[a];  // predicted velocity for the viscous force
    ps_.vy[a] = vhy[k] + 0.5 * dt * ay_[a];
  }
  compute_accelerations();
  for (std::size_t k = 0; k < m; ++k) {
    const int a = moving_[k];
    ps_.vx[a] = vhx[k] + 0.5 * dt * ax_[a];
    ps_.vy[a] = vhy[k] + 0.5 * dt * ay_[a];
  }
}

double SphEngine::max_speed() const {
  double v2 = 0.0;
  for (int a : moving_) v2 = std::max(v2, ps_.vx[a] * ps_.vx[a] + ps_.vy[a] * ps_.vy[a]);
  return std::sqrt(v2);
}

double SphEngine::time_step(double kappa) const {
  const double dx = scene_.dx;
  return kappa * std::min(dx / (scene_.sound_speed + max_speed()),
                          scene_.rho0 * dx * dx / (scene_.max_viscosity() * viscous_stiffening_));
}

std::vector<PairForce> SphEngine::pair_forces() {
  compute_density();
  std::vector<PairForce> out;
  out.reserve(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const double F = pair_f_[p];
    if (F == 0.0) continue;
    const int i = pairs_.i[p], j = pairs_.j[p];
    const Vec2 q_ij(pair_dx_[p], pair_dy_[p]);
    const Vec2 f = pair_force(p, pressure(i) / (n_[i] * n_[i]), pressure(j) / (n_[j] * n_[j]));
    out.push_back({i, j, -q_ij, f});
  }
  return out;
}

}  // namespace closurelab
