// The direct SPH engine. Over 300 lines: the two pair passes, their per-particle steps and the list upkeep share
// the engine's state and are kept together.
#include "core/sph/sph_engine.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "core/base/errors.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab {

// The Verlet list as the passes read it: pairs (i, j), i < j, grouped by i into rows (j ascending), rows into
// blocks of about 256 pairs, the unit of the passes and of their threads.
struct PairBlocks {
  const std::int32_t *pi, *pj;  // the listed pairs, grouped by i
  const std::int32_t* row_i;    // row r: particle i of the listed pairs [row_begin[r], row_begin[r + 1])
  const std::uint32_t* row_begin;
  const std::uint32_t* block_row;  // block b: rows [block_row[b], block_row[b + 1])
};

namespace {

// A second compilation of the density kernel loop for AVX2, chosen at run time, where the baseline lacks it.
#if defined(__x86_64__) && !defined(__AVX2__)
#define CLOSURELAB_AVX2_CLONE 1
#else
#define CLOSURELAB_AVX2_CLONE 0
#endif

std::atomic<PairKernelIsa>& chosen_isa() {
  static std::atomic<PairKernelIsa> isa{[] {
#if CLOSURELAB_AVX2_CLONE
    if (__builtin_cpu_supports("avx2")) return PairKernelIsa::avx2;
#endif
    return PairKernelIsa::baseline;
  }()};
  return isa;
}

// Minimum image along a periodic axis, d − L rint(d/L), with rint as the round-to-nearest shift by 1.5·2⁵²
// (exact for |d/L| < 2⁵¹) and 1/L precomputed: no library call in the pair loop. For the listed pairs
// (|d| far from L/2) it equals PeriodicBox::wrap_dx bitwise. With 1/L = 0 (an axis that is not periodic) it
// returns d unchanged: no branch.
inline double wrap(double d, double len, double inv_len) {
  constexpr double shift = 6755399441055744.0;
  const double k = (d * inv_len + shift) - shift;
  return d - len * k;
}

// A block's listed pairs: q_i − q_j and w'/r per pair into the list's arrays, w into the block's scratch; no
// store to a particle, so the compiler vectorizes it (gathers of the positions; the square root, division and
// max of several pairs in one vector register).
template <SmoothingKernel::Type T>
inline void density_kernel(const SmoothingKernel kernel, double lx, double ly, double ilx, double ily,
                           const double* __restrict x, const double* __restrict y, const std::int32_t* __restrict pi,
                           const std::int32_t* __restrict pj, std::size_t len, double* __restrict qx,
                           double* __restrict qy, double* __restrict dw_over_r, double* __restrict w) {
#pragma omp simd
  for (std::size_t k = 0; k < len; ++k) {
    const int i = pi[k], j = pj[k];
    const double dx = wrap(x[i] - x[j], lx, ilx), dy = wrap(y[i] - y[j], ly, ily);
    qx[k] = dx;
    qy[k] = dy;
    kernel.w_and_dw_over_r<T>(dx * dx + dy * dy, w[k], dw_over_r[k]);
  }
}

#if CLOSURELAB_AVX2_CLONE
// The same loop compiled for AVX2 (four pairs per vector). AVX2 without FMA: every operation is rounded as in the
// baseline, so both give the same bits (test SphEngineVectorKernels).
template <SmoothingKernel::Type T>
[[gnu::target("avx2")]] void density_kernel_avx2(const SmoothingKernel kernel, double lx, double ly, double ilx,
                                                 double ily, const double* __restrict x, const double* __restrict y,
                                                 const std::int32_t* __restrict pi, const std::int32_t* __restrict pj,
                                                 std::size_t len, double* __restrict qx, double* __restrict qy,
                                                 double* __restrict dw_over_r, double* __restrict w) {
  density_kernel<T>(kernel, lx, ly, ilx, ily, x, y, pi, pj, len, qx, qy, dw_over_r, w);
}
#endif

// The density pass over blocks [b0, b1): per block the kernel loop, then row by row w added to the densities in
// n: particle i's sum kept in a register over its row, only j's scattered (a pair-by-pair scatter chains through
// memory whenever consecutive pairs share a particle). Listed pairs beyond the support give w = w'/r = 0.
template <SmoothingKernel::Type T>
void density_blocks(const SmoothingKernel kernel, const PeriodicBox box, const double* __restrict x,
                    const double* __restrict y, const PairBlocks& g, std::size_t b0, std::size_t b1,
                    double* __restrict qx, double* __restrict qy, double* __restrict dw_over_r, double* __restrict w,
                    double* __restrict n, [[maybe_unused]] PairKernelIsa isa) {
  const double lx = box.lx, ly = box.ly;
  const double ilx = box.periodic_x ? 1.0 / lx : 0.0, ily = box.periodic_y ? 1.0 / ly : 0.0;
  for (std::size_t b = b0; b < b1; ++b) {
    const std::size_t r0 = g.block_row[b], r1 = g.block_row[b + 1];
    const std::size_t p0 = g.row_begin[r0], len = g.row_begin[r1] - p0;
#if CLOSURELAB_AVX2_CLONE
    if (isa == PairKernelIsa::avx2)
      density_kernel_avx2<T>(kernel, lx, ly, ilx, ily, x, y, g.pi + p0, g.pj + p0, len, qx + p0, qy + p0,
                             dw_over_r + p0, w);
    else
#endif
      density_kernel<T>(kernel, lx, ly, ilx, ily, x, y, g.pi + p0, g.pj + p0, len, qx + p0, qy + p0, dw_over_r + p0, w);
    for (std::size_t r = r0; r < r1; ++r) {
      double sum = 0.0;
      for (std::size_t p = g.row_begin[r], e = g.row_begin[r + 1]; p < e; ++p) {
        sum += w[p - p0];
        n[g.pj[p]] += w[p - p0];
      }
      n[g.row_i[r]] += sum;
    }
  }
}

// Inputs of the force pass.
struct ForceInputs {
  const SphPairInput* s;
  const double* mu;
  const int* phase;
  PairViscosityMean mean;
  double unlike;     // added to P_i/n_i² + P_j/n_j² of an unlike pair: twice the excess of (7.1)
  double mu_single;  // μ_ij of a one-phase scene (2μ, as pair_viscosity gives for like particles)
};

// (5.1) for pair (i, j) with relative velocity v_i − v_j: the force on i. OnePhase: every pair is a like pair.
template <bool OnePhase>
inline void force_pair(const ForceInputs& in, int i, int j, double F, double qx, double qy, double& fx, double& fy) {
  const SphPairInput &a = in.s[i], &b = in.s[j];
  double p_sum = a.p_over_n2 + b.p_over_n2, mu_ij = in.mu_single;
  if constexpr (!OnePhase) {
    p_sum += in.phase[i] != in.phase[j] ? in.unlike : 0.0;
    mu_ij = pair_viscosity(in.mu[i], in.mu[j], in.mean);
  }
  sph_pair_force(p_sum, mu_ij * (a.inv_n * b.inv_n), F, qx, qy, a.vx - b.vx, a.vy - b.vy, fx, fy);
}

// The force pass over rows [r0, r1): the force on i of each listed pair from `pair` (i, j, p) -> (fx, fy), summed
// over the row in registers, its opposite added to each j.
template <class PairForceOnI>
void force_rows(const PairBlocks& g, std::size_t r0, std::size_t r1, PairForceOnI pair, double* __restrict f) {
  for (std::size_t r = r0; r < r1; ++r) {
    const int i = g.row_i[r];
    double sx = 0.0, sy = 0.0;
    for (std::size_t p = g.row_begin[r], e = g.row_begin[r + 1]; p < e; ++p) {
      const int j = g.pj[p];
      double fx, fy;
      pair(i, j, p, fx, fy);
      sx += fx;
      sy += fy;
      f[2 * j] -= fx;
      f[2 * j + 1] -= fy;
    }
    f[2 * i] += sx;
    f[2 * i + 1] += sy;
  }
}

}  // namespace

bool pair_kernel_isa_available(PairKernelIsa isa) {
#if CLOSURELAB_AVX2_CLONE
  if (isa == PairKernelIsa::avx2) return __builtin_cpu_supports("avx2");
#else
  if (isa == PairKernelIsa::avx2) return false;
#endif
  return true;
}

PairKernelIsa pair_kernel_isa() { return chosen_isa().load(); }

void set_pair_kernel_isa(PairKernelIsa isa) {
  if (!pair_kernel_isa_available(isa))
    throw std::invalid_argument("set_pair_kernel_isa: this build or CPU has no " + name_of(isa) + " pair kernel");
  chosen_isa().store(isa);
}

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
  thread_buf_.assign(omp_get_max_threads(), std::vector<double>(2 * n, 0.0));
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
      if (box.periodic_x) dx = wrap(dx, box.lx, inv_lx_);
      if (box.periodic_y) dy = wrap(dy, box.ly, inv_ly_);
      need |= dx * dx + dy * dy > limit2 ? 1 : 0;
    }
    if (!need) return;
  }
  const auto& fixed = ps_.fixed;
  pairs_ = find_pairs(ps_, active_, scene_.box, w_.support() + skin_,
                      [&fixed](int a, int b) { return !(fixed[a] && fixed[b]); });
  group_pairs_by_particle();
  x_built_ = ps_.x;
  y_built_ = ps_.y;
  pair_dx_.resize(pairs_.size());
  pair_dy_.resize(pairs_.size());
  pair_f_.resize(pairs_.size());
  built_ = true;
  ++list_rebuilds_;
}

// Orders the list by its first particle i (counting sort; within a row by j, so the scatter walks memory upwards)
// and cuts the rows into blocks of about kBlockPairs pairs, the unit of the passes and of their threads.
void SphEngine::group_pairs_by_particle() {
  constexpr std::size_t kBlockPairs = 256;
  const std::size_t np = pairs_.size(), n = ps_.size();
  std::vector<std::uint32_t> begin(n + 1, 0);
  for (std::size_t p = 0; p < np; ++p) ++begin[pairs_.i[p] + 1];
  for (std::size_t a = 0; a < n; ++a) begin[a + 1] += begin[a];
  PairList grouped;
  grouped.i.resize(np);
  grouped.j.resize(np);
  std::vector<std::uint32_t> next(begin.begin(), begin.end() - 1);
  for (std::size_t p = 0; p < np; ++p) {
    const std::uint32_t q = next[pairs_.i[p]]++;
    grouped.i[q] = pairs_.i[p];
    grouped.j[q] = pairs_.j[p];
  }
  pairs_ = std::move(grouped);
  row_i_.clear();
  row_begin_.clear();
  block_row_.assign(1, 0);
  std::size_t block_start = 0, longest = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (begin[a + 1] == begin[a]) continue;
    std::sort(pairs_.j.begin() + begin[a], pairs_.j.begin() + begin[a + 1]);
    if (begin[a] - block_start >= kBlockPairs) {
      block_row_.push_back(static_cast<std::uint32_t>(row_i_.size()));
      longest = std::max<std::size_t>(longest, begin[a] - block_start);
      block_start = begin[a];
    }
    row_i_.push_back(static_cast<std::int32_t>(a));
    row_begin_.push_back(begin[a]);
  }
  row_begin_.push_back(static_cast<std::uint32_t>(np));
  if (!row_i_.empty()) block_row_.push_back(static_cast<std::uint32_t>(row_i_.size()));
  longest = std::max<std::size_t>(longest, np - block_start);
  for (auto& scratch : thread_scratch_) scratch.resize(longest);
}

PairBlocks SphEngine::blocks() const {
  return {pairs_.i.data(), pairs_.j.data(), row_i_.data(), row_begin_.data(), block_row_.data()};
}

void SphEngine::compute_density() {
  rebuild_pairs_if_needed();
  const double w0 = w_.w(0.0);
  const std::size_t np = pairs_.size(), n = ps_.size(), na = active_.size();
  const bool quintic = w_.type() == SmoothingKernel::Type::quintic;
  const PairBlocks g = blocks();
  const std::size_t nb = block_row_.size() - 1;
  const PairKernelIsa isa = pair_kernel_isa();
#pragma omp parallel num_threads(static_cast <int>(thread_buf_.size()))
  {
    const std::size_t t = omp_get_thread_num(), nt = omp_get_num_threads();
    auto& buf = thread_buf_[t];
    std::fill(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n), 0.0);
    const std::size_t b0 = nb * t / nt, b1 = nb * (t + 1) / nt;
    double* w = thread_scratch_[t].data();
    if (quintic)
      density_blocks<SmoothingKernel::Type::quintic>(w_, scene_.box, ps_.x.data(), ps_.y.data(), g, b0, b1,
                                                     pair_dx_.data(), pair_dy_.data(), pair_f_.data(), w, buf.data(),
                                                     isa);
    else
      density_blocks<SmoothingKernel::Type::wendland_c2>(w_, scene_.box, ps_.x.data(), ps_.y.data(), g, b0, b1,
                                                         pair_dx_.data(), pair_dy_.data(), pair_f_.data(), w,
                                                         buf.data(), isa);
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < na; ++k) {
      const int a = active_[k];
      double sum = ps_.fixed[a] ? n_static_[a] : w0;
      for (std::size_t u = 0; u < nt; ++u) sum += thread_buf_[u][a];
      n_[a] = sum;
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
  const bool lower = ps_.y[w] < scene_.wall_lo;
  const double d_wall = lower ? scene_.wall_lo - ps_.y[w] : ps_.y[w] - scene_.wall_hi;
  const double d_fluid = std::max(lower ? ps_.y[f] - scene_.wall_lo : scene_.wall_hi - ps_.y[f], 1e-3 * scene_.dx);
  const double beta = std::min(scene_.ghost_beta_max, 1.0 + d_wall / d_fluid);
  const double sign = fa ? -1.0 : 1.0;
  return {sign * beta * ps_.vx[f], sign * beta * ps_.vy[f]};
}

void SphEngine::force_rows_of_thread(std::size_t t, std::size_t nt) {
  const ForceInputs in{pair_input_.data(),         mu_.data(),           ps_.phase.data(),
                       scene_.pair_viscosity_mean, 2.0 * unlike_excess_, mu_.empty() ? 0.0 : mu_[0] + mu_[0]};
  const PairBlocks g = blocks();
  const std::size_t nb = block_row_.size() - 1;
  const std::size_t r0 = block_row_[nb * t / nt], r1 = block_row_[nb * (t + 1) / nt];
  double* f = thread_buf_[t].data();
  const double *F = pair_f_.data(), *qx = pair_dx_.data(), *qy = pair_dy_.data();
  if (scene_.wall_model != WallModel::ghost_velocity) {
    if (one_phase_)
      force_rows(
          g, r0, r1,
          [&](int i, int j, std::size_t p, double& fx, double& fy) {
            force_pair<true>(in, i, j, F[p], qx[p], qy[p], fx, fy);
          },
          f);
    else
      force_rows(
          g, r0, r1,
          [&](int i, int j, std::size_t p, double& fx, double& fy) {
            force_pair<false>(in, i, j, F[p], qx[p], qy[p], fx, fy);
          },
          f);
    return;
  }
  // Ghost walls: fluid–wall pairs take their ghost velocity.
  const std::uint8_t* fixed = ps_.fixed.data();
  force_rows(
      g, r0, r1,
      [&](int i, int j, std::size_t p, double& fx, double& fy) {
        if (fixed[i] == fixed[j] || F[p] == 0.0) {
          force_pair<false>(in, i, j, F[p], qx[p], qy[p], fx, fy);
          return;
        }
        const Vec2 v = pair_force(i, j, p, pair_input_[i].p_over_n2, pair_input_[j].p_over_n2);
        fx = v.x();
        fy = v.y();
      },
      f);
}

void SphEngine::compute_accelerations() {
  compute_density();
  const std::size_t n = ps_.size(), na = active_.size(), m = moving_.size();
#pragma omp parallel num_threads(static_cast <int>(thread_buf_.size()))
  {
    const std::size_t t = omp_get_thread_num(), nt = omp_get_num_threads();
    auto& buf = thread_buf_[t];
    std::fill(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(2 * n), 0.0);
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < na; ++k) {
      const int a = active_[k];
      pair_input_[a] = {pressure(a) / (n_[a] * n_[a]), 1.0 / n_[a], ps_.vx[a], ps_.vy[a]};
    }
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
  const double dx = scene_.dx;
  return kappa * std::min(dx / (scene_.sound_speed + max_speed()),
                          scene_.rho0 * dx * dx / (scene_.max_viscosity() * viscous_stiffening_));
}

std::vector<PairForce> SphEngine::pair_forces() {
  compute_density();
  std::vector<PairForce> out;
  out.reserve(pairs_.size());
  for (std::size_t r = 0; r < row_i_.size(); ++r) {
    const int i = row_i_[r];
    for (std::size_t p = row_begin_[r]; p < row_begin_[r + 1]; ++p) {
      if (pair_f_[p] == 0.0) continue;
      const int j = pairs_.j[p];
      const Vec2 q_ij(pair_dx_[p], pair_dy_[p]);
      const Vec2 f = pair_force(i, j, p, pressure(i) / (n_[i] * n_[i]), pressure(j) / (n_[j] * n_[j]));
      out.push_back({i, j, -q_ij, f});
    }
  }
  return out;
}

}  // namespace closurelab
