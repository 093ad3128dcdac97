// The direct SPH engine: its state, the list upkeep (search and rebuild test), the per-particle steps of the
// two pair passes and the integrator; the pair loops themselves are in sph_pair_passes.hpp, the transport-velocity
// formulation's passes and step in sph_engine_transport.cpp. Above the 320-line guide by the constructor's setup
// (the active set, the walls' static densities, the viscosities), which the passes read and nothing else uses.
#include "core/sph/sph_engine.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/base/errors.hpp"
#include "core/sph/sph_pair_force.hpp"
#include "core/sph/sph_pair_passes.hpp"

namespace closurelab {

SphEngine::SphEngine(const Scene& scene, ParticleSystem& particles, const SphEngineOptions& options)
    : scene_(scene), ps_(particles), options_(options), w_(scene.smoothing_kernel()) {
  transport_ = options_.formulation == SphFormulation::transport_velocity;
  if (transport_) {
    if (scene.wall_model == WallModel::ghost_velocity)
      throw std::invalid_argument("the transport-velocity formulation has its own wall condition (Adami, Hu & Adams "
                                  "2012): scene '" + scene.name + "' asks for ghost-velocity walls");
    if (!(options_.transport_background_pressure_factor > 0.0))
      throw std::invalid_argument("the transport velocity's background pressure must be positive");
  }
  // The list radius is support + skin. A skin of 0.15 ε' keeps the lattice's ring at √10 ε' (8 of the 36
  // neighbours a skin of ε'/2 lists, all beyond the support 3ε') out of the list: the density pass takes 28
  // neighbours per particle instead of 36. The list is rebuilt after a displacement of 0.075 ε' instead of 0.25 ε'
  // (75 rebuilds instead of 23 in a steady channel run of 44 000 steps at n_y = 96: a small share of its time).
  // Listed pairs beyond the support add exact zeros, so the skin changes no bit of a one-thread run (on more
  // threads the rows' split among them follows the list: round-off, as between thread counts).
  skin_ = 0.15 * scene.dx;
  mass_ = scene.particle_mass();
  const std::size_t n = ps_.size();
  // Fixed particles (walls, solids) take part where a moving particle can reach them: within the list radius
  // (support + skin) plus one spacing of drift of some moving particle at the start. Those farther away can
  // only pair with a moving particle that has drifted by more than a spacing towards the solid.
  const double reach = w_.support() + skin_ + scene.dx;
  const std::vector<std::uint8_t> near = fixed_within_reach_of_moving(ps_, scene.box, reach);
  std::vector<std::int32_t> walls;
  for (std::size_t a = 0; a < n; ++a) {
    if (!ps_.fixed[a]) {
      moving_.push_back(static_cast<std::int32_t>(a));
      active_.push_back(static_cast<std::int32_t>(a));
      continue;
    }
    walls.push_back(static_cast<std::int32_t>(a));
    if (near[a]) active_.push_back(static_cast<std::int32_t>(a));
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
  thread_buf_.assign(omp_get_max_threads(), std::vector<double>((transport_ ? 4 : 2) * n, 0.0));
  thread_scratch_.assign(thread_buf_.size(), {});
  pair_input_.assign(n, SphPairInput{0.0, 0.0, 0.0, 0.0});
  for (std::size_t a = 1; a < n; ++a) one_phase_ = one_phase_ && ps_.phase[a] == ps_.phase[0];
  inv_lx_ = 1.0 / scene.box.lx;
  inv_ly_ = 1.0 / scene.box.ly;
  // The ghost-velocity wall multiplies the viscous coupling of a fluid–wall pair by β <= 1 + d_wall/d_fluid;
  // with the wall between lattice rows, d_fluid >= ε'/2 and d_wall < support.
  viscous_stiffening_ = scene.wall_model == WallModel::ghost_velocity
                            ? std::min(scene.ghost_beta_max, 1.0 + w_.support() / (0.5 * scene.dx))
                            : 1.0;
  if (transport_) {
    transport_eps_ = 0.01 * w_.h() * w_.h();  // PySPH's EPS = 0.01 HIJ²
    background_pressure_ = options_.transport_background_pressure_factor * scene.rho0 * scene.sound_speed * scene.sound_speed;
    tvf_input_.assign(n, TvfParticle{});
    transport_walls_ = !walls.empty();
    stress_weight_.assign(n, 1.0);
    for (int a : walls) stress_weight_[a] = 0.0;
    bx_.assign(n, 0.0);
    by_.assign(n, 0.0);
  }
}

void SphEngine::rebuild_pairs_if_needed() {
  if (built_) {
    const double limit2 = 0.25 * skin_ * skin_;
    const std::size_t m = moving_.size();
    const PeriodicBox& box = scene_.box;
    int need = 0;
#pragma omp parallel for num_threads(static_cast <int>(thread_buf_.size())) schedule(static) reduction(| : need)
    for (std::size_t k = 0; k < m; ++k) {
      const int a = moving_[k];
      double dx = ps_.x[a] - x_built_[a], dy = ps_.y[a] - y_built_[a];
      if (box.periodic_x) dx = pair_passes::wrap(dx, box.lx, inv_lx_);
      if (box.periodic_y) dy = pair_passes::wrap(dy, box.ly, inv_ly_);
      need |= dx * dx + dy * dy > limit2 ? 1 : 0;
    }
    if (!need) return;
  }
  const auto& fixed = ps_.fixed;
  list_ = group_by_first_particle(find_pairs(ps_, active_, scene_.box, w_.support() + skin_,
                                             [&fixed](int a, int b) { return !(fixed[a] && fixed[b]); }),
                                  ps_.size());
  for (auto& scratch : thread_scratch_) scratch.resize(list_.longest_block);
  x_built_ = ps_.x;
  y_built_ = ps_.y;
  pair_dx_.resize(list_.pairs.size());
  pair_dy_.resize(list_.pairs.size());
  pair_f_.resize(list_.pairs.size());
  if (transport_walls_) {
    wall_pairs_.clear();
    for (std::size_t p = 0; p < list_.pairs.size(); ++p)
      if (fixed[list_.pairs.i[p]] != fixed[list_.pairs.j[p]]) wall_pairs_.push_back(p);
  }
  built_ = true;
  ++list_rebuilds_;
}

PairBlocks SphEngine::blocks() const {
  return {list_.pairs.i.data(), list_.pairs.j.data(), list_.row_i.data(), list_.row_begin.data(),
          list_.block_row.data()};
}

void SphEngine::compute_density() {
  rebuild_pairs_if_needed();
  const double w0 = w_.w(0.0);
  const std::size_t np = list_.pairs.size(), n = ps_.size(), na = active_.size();
  const bool quintic = w_.type() == SmoothingKernel::Type::quintic;
  const PairBlocks g = blocks();
  const std::size_t nb = list_.block_row.size() - 1;
  const PairKernelIsa isa = pair_kernel_isa();
#pragma omp parallel num_threads(static_cast <int>(thread_buf_.size()))
  {
    const std::size_t t = omp_get_thread_num(), nt = omp_get_num_threads();
    auto& buf = thread_buf_[t];
    std::fill(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n), 0.0);
    const std::size_t b0 = nb * t / nt, b1 = nb * (t + 1) / nt;
    double* w = thread_scratch_[t].data();
    if (quintic)
      pair_passes::density_blocks<SmoothingKernel::Type::quintic>(w_, scene_.box, ps_.x.data(), ps_.y.data(), g, b0, b1,
                                                                  pair_dx_.data(), pair_dy_.data(), pair_f_.data(), w,
                                                                  buf.data(), isa);
    else
      pair_passes::density_blocks<SmoothingKernel::Type::wendland_c2>(w_, scene_.box, ps_.x.data(), ps_.y.data(), g, b0,
                                                                      b1, pair_dx_.data(), pair_dy_.data(),
                                                                      pair_f_.data(), w, buf.data(), isa);
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < na; ++k) {
      const int a = active_[k];
      double sum = ps_.fixed[a] ? n_static_[a] : w0;
      for (std::size_t u = 0; u < nt; ++u) sum += thread_buf_[u][a];
      n_[a] = sum;
      pair_input_[a] = {pressure(a) / (sum * sum), 1.0 / sum, ps_.vx[a], ps_.vy[a]};  // the force pass's inputs
    }
  }
  pair_evaluations_ += static_cast<std::int64_t>(np);
}

double SphEngine::pressure(std::int32_t a) const { return scene_.pressure(n_[a], ps_.mass[a]); }

Vec2 SphEngine::pair_force(std::int32_t i, std::int32_t j, std::size_t p, double p_over_n2_i,
                           double p_over_n2_j) const {
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
  if (scene_.wall_model == WallModel::zero_velocity || fa == fb) return {ps_.vx[a] - ps_.vx[b], ps_.vy[a] - ps_.vy[b]};
  // Ghost velocity: the wall particle moves with −(d_wall / d_fluid) v_fluid, so that the velocity
  // continued across the wall surface vanishes on it.
  const int f = fa ? b : a, w = fa ? a : b;
  double d_wall, d_fluid;
  if (scene_.solid_depth && !scene_.is_wall(ps_.y[w])) {  // a solid given by position (scene.hpp)
    d_wall = scene_.solid_depth(ps_.x[w], ps_.y[w]);
    d_fluid = std::max(-scene_.solid_depth(ps_.x[f], ps_.y[f]), 1e-3 * scene_.dx);
  } else {
    const bool lower = ps_.y[w] < scene_.wall_lo;
    d_wall = lower ? scene_.wall_lo - ps_.y[w] : ps_.y[w] - scene_.wall_hi;
    d_fluid = std::max(lower ? ps_.y[f] - scene_.wall_lo : scene_.wall_hi - ps_.y[f], 1e-3 * scene_.dx);
  }
  const double beta = std::min(scene_.ghost_beta_max, 1.0 + d_wall / d_fluid);
  const double sign = fa ? -1.0 : 1.0;
  return {sign * beta * ps_.vx[f], sign * beta * ps_.vy[f]};
}

void SphEngine::force_rows_of_thread(std::size_t t, std::size_t nt) {
  const pair_passes::ForceInputs in{pair_input_.data(),   mu_.data(),
                                    ps_.phase.data(),     scene_.pair_viscosity_mean,
                                    2.0 * unlike_excess_, mu_.empty() ? 0.0 : mu_[0] + mu_[0]};
  const PairBlocks g = blocks();
  const std::size_t nb = list_.block_row.size() - 1;
  const std::size_t r0 = list_.block_row[nb * t / nt], r1 = list_.block_row[nb * (t + 1) / nt];
  double* f = thread_buf_[t].data();
  const double *F = pair_f_.data(), *qx = pair_dx_.data(), *qy = pair_dy_.data();
  if (scene_.wall_model != WallModel::ghost_velocity) {
    if (one_phase_)
      pair_passes::force_rows(
          g, r0, r1, F,
          [&](int i, int j, std::size_t p, double& fx, double& fy) {
            pair_passes::force_pair<true>(in, i, j, F[p], qx[p], qy[p], fx, fy);
          },
          f);
    else
      pair_passes::force_rows(
          g, r0, r1, F,
          [&](int i, int j, std::size_t p, double& fx, double& fy) {
            pair_passes::force_pair<false>(in, i, j, F[p], qx[p], qy[p], fx, fy);
          },
          f);
    return;
  }
  // Ghost walls: fluid–wall pairs take their ghost velocity.
  const std::uint8_t* fixed = ps_.fixed.data();
  pair_passes::force_rows(
      g, r0, r1, F,
      [&](int i, int j, std::size_t p, double& fx, double& fy) {
        if (fixed[i] == fixed[j]) {
          pair_passes::force_pair<false>(in, i, j, F[p], qx[p], qy[p], fx, fy);
          return;
        }
        const Vec2 v = pair_force(i, j, p, pair_input_[i].p_over_n2, pair_input_[j].p_over_n2);
        fx = v.x();
        fy = v.y();
      },
      f);
}

void SphEngine::compute_accelerations() {
  if (transport_) {
    compute_transport_accelerations();
    return;
  }
  compute_density();
  const std::size_t n = ps_.size(), m = moving_.size();
#pragma omp parallel num_threads(static_cast <int>(thread_buf_.size()))
  {
    const std::size_t t = omp_get_thread_num(), nt = omp_get_num_threads();
    auto& buf = thread_buf_[t];
    std::fill(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(2 * n), 0.0);
    force_rows_of_thread(t, nt);
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < m; ++k) {
      const int a = moving_[k];
      double fx = 0.0, fy = 0.0;
      for (std::size_t u = 0; u < nt; ++u) fx += thread_buf_[u][2 * a], fy += thread_buf_[u][2 * a + 1];
      ax_[a] = fx / ps_.mass[a];
      ay_[a] = fy / ps_.mass[a];
      if (scene_.body_force) {
        const Vec2 g = scene_.body_force(ps_.x[a], ps_.y[a]);
        ax_[a] += g.x();
        ay_[a] += g.y();
      } else {
        ax_[a] += scene_.force_x(ps_.y[a]);
      }
    }
  }
}

void SphEngine::step(double dt) {
  if (transport_) {
    transport_step(dt);
    return;
  }
  if (!built_) compute_accelerations();
  const std::size_t m = moving_.size();
  vhx_.resize(m);
  vhy_.resize(m);
  const PeriodicBox& box = scene_.box;
#pragma omp parallel for num_threads(static_cast <int>(thread_buf_.size())) schedule(static)
  for (std::size_t k = 0; k < m; ++k) {
    const int a = moving_[k];
    vhx_[k] = ps_.vx[a] + 0.5 * dt * ax_[a];
    vhy_[k] = ps_.vy[a] + 0.5 * dt * ay_[a];
    double x = ps_.x[a] + dt * vhx_[k];
    if (box.periodic_x) x -= box.lx * std::floor(x / box.lx);
    double y = ps_.y[a] + dt * vhy_[k];
    if (box.periodic_y) y -= box.ly * std::floor(y / box.ly);
    ps_.x[a] = x;
    ps_.y[a] = y;
    ps_.vx[a] = vhx_[k] + 0.5 * dt * ax_[a];  // predicted velocity for the viscous force
    ps_.vy[a] = vhy_[k] + 0.5 * dt * ay_[a];
  }
  compute_accelerations();
#pragma omp parallel for num_threads(static_cast <int>(thread_buf_.size())) schedule(static)
  for (std::size_t k = 0; k < m; ++k) {
    const int a = moving_[k];
    ps_.vx[a] = vhx_[k] + 0.5 * dt * ax_[a];
    ps_.vy[a] = vhy_[k] + 0.5 * dt * ay_[a];
  }
}

double SphEngine::max_speed() const {
  double v2 = 0.0;
  for (int a : moving_) v2 = std::max(v2, ps_.vx[a] * ps_.vx[a] + ps_.vy[a] * ps_.vy[a]);
  return std::sqrt(v2);
}

double SphEngine::time_step(double kappa) const {
  if (transport_) {
    const double h = w_.h(), u = std::max(scene_.analytic_peak, max_speed());
    return std::min(kappa * h / (scene_.sound_speed + u), 0.5 * kappa * scene_.rho0 * h * h / scene_.max_viscosity());
  }
  const double dx = scene_.dx;
  return kappa * std::min(dx / (scene_.sound_speed + max_speed()),
                          scene_.rho0 * dx * dx / (scene_.max_viscosity() * viscous_stiffening_));
}

std::vector<PairForce> SphEngine::pair_forces() {
  compute_density();
  if (transport_) {
    prepare_transport_inputs();
    apply_transport_wall_condition();
  }
  std::vector<PairForce> out;
  out.reserve(list_.pairs.size());
  for (std::size_t r = 0; r < list_.row_i.size(); ++r) {
    const int i = list_.row_i[r];
    for (std::size_t p = list_.row_begin[r]; p < list_.row_begin[r + 1]; ++p) {
      if (pair_f_[p] == 0.0) continue;
      const int j = list_.pairs.j[p];
      const Vec2 q_ij(pair_dx_[p], pair_dy_[p]);
      if (transport_) {  // the momentum force of the transport-velocity formulation (its background part aside)
        double fx, fy, bx, by;
        tvf_pair_force<true>(tvf_input_[i], tvf_input_[j], pair_f_[p], pair_dx_[p], pair_dy_[p], transport_eps_,
                             background_pressure_, fx, fy, bx, by, ps_.fixed[i] || ps_.fixed[j] ? 0.0 : 1.0);
        out.push_back({i, j, -q_ij, Vec2(fx, fy)});
        continue;
      }
      const Vec2 f = pair_force(i, j, p, pressure(i) / (n_[i] * n_[i]), pressure(j) / (n_[j] * n_[j]));
      out.push_back({i, j, -q_ij, f});
    }
  }
  return out;
}

}  // namespace closurelab
