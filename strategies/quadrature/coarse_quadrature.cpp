#include "strategies/quadrature/coarse_quadrature.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include "core/base/errors.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_pair_force.hpp"
#include "strategies/quadrature/bond_weights.hpp"

namespace closurelab {

namespace {

std::string divisors_of(int n) {
  std::string s;
  for (int d = 1; d <= n; ++d)
    if (n % d == 0) s += (s.empty() ? "" : ", ") + std::to_string(d);
  return s;
}

}  // namespace

CoarseQuadrature::CoarseQuadrature(int stride_x, int stride_y, bool refine_walls)
    : stride_x_(stride_x), stride_y_(stride_y), refine_walls_(refine_walls) {
  if (stride_x < 0) throw ConfigError("/stride_x", "must be >= 0 (0: x-integrated, for x-invariant scenes)");
  if (stride_y < 1) throw ConfigError("/stride_y", "must be >= 1");
}

void CoarseQuadrature::setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
                             const std::vector<std::string>& components) {
  const auto t0 = std::chrono::steady_clock::now();
  // The R-grid must tile the lattice: N/N_C = s_x s_y with whole blocks of sites.
  if (scene.ny % stride_y_ != 0)
    throw ConfigError("/stride_y", "the R-grid stride " + std::to_string(stride_y_) + " does not divide the lattice's n_y = " +
                                       std::to_string(scene.ny) + "; allowed strides: " + divisors_of(scene.ny));
  const bool x_integrated = stride_x_ == 0;
  if (x_integrated && !scene.x_invariant)
    throw ConfigError("/stride_x", "0 (x-integrated R-grid) needs an x-invariant scene; scene '" + scene.name +
                                       "' is not: give a stride dividing n_x = " + std::to_string(scene.nx));
  if (!x_integrated && scene.nx % stride_x_ != 0)
    throw ConfigError("/stride_x", "the R-grid stride " + std::to_string(stride_x_) + " does not divide the lattice's n_x = " +
                                       std::to_string(scene.nx) + "; allowed strides: " + divisors_of(scene.nx) +
                                       (scene.x_invariant ? " (or 0: x-integrated)" : ""));
  check_mesh_matches_box(nodes, scene.box);
  comp_index_ = component_indices(components);
  components_ = components;
  node_count_ = nodes.size();

  const SmoothingKernel w = SmoothingKernel::from_name(scene.smoothing_kernel, scene.h);
  const double dx = scene.dx, rs = w.support();
  n_star_ = scene.lattice_number_density();
  p_over_n2_ = scene.rest_pressure() / (n_star_ * n_star_);
  // Fine lattice offsets ρ_j of the SPH support (the engine's interacting pairs: 0 < |ρ| < support).
  std::vector<std::pair<int, int>> offsets;
  const int reach = static_cast<int>(std::ceil(rs / dx));
  for (int oy = -reach; oy <= reach; ++oy)
    for (int ox = -reach; ox <= reach; ++ox) {
      const double r = dx * std::hypot(ox, oy);
      if (r > 0.0 && r * r < rs * rs) offsets.emplace_back(ox, oy);
    }
  offsets_ = static_cast<int>(offsets.size());

  // Positions in half lattice units: h ↦ h ε'/2, so lattice site i sits at h = 2i + 1 and the centre of a run
  // of L sites starting at i0 at h = 2 i0 + L (a site when L is odd, between two when L is even).
  const int sx = x_integrated ? scene.nx : stride_x_, sy = stride_y_;
  struct Run {
    int centre, sites;  // centre in half units; the lattice sites it stands for
  };
  std::vector<Run> cols, rows;
  if (x_integrated)
    cols = {{1, scene.nx}};  // one column per strip period (x-integrated weights)
  else
    for (int m = 0; m < scene.nx / sx; ++m) cols.push_back({2 * m * sx + sx, sx});
  // R-rows: the centres of blocks of s_y rows (the coarse cells' centres q_β). With refined wall bands, rows
  // within one SPH support of a wall surface (where bonds straddle the wall and the integrand of (5.25)
  // jumps) are R-rows of their own, and each contiguous rest of a block is one R-row at its centre.
  const auto near_wall = [&](int j) {
    const double y = (j + 0.5) * dx;
    return refine_walls_ && scene.has_walls && (std::abs(y - scene.wall_lo) < rs || std::abs(y - scene.wall_hi) < rs);
  };
  for (int m = 0; m < scene.ny / sy; ++m) {
    int start = m * sy;
    for (int j = m * sy; j <= (m + 1) * sy; ++j) {
      const bool end = j == (m + 1) * sy;
      if (!end && !near_wall(j)) continue;
      if (j > start) rows.push_back({2 * start + (j - start), j - start});
      if (!end) rows.push_back({2 * j + 1, 1});
      start = j + 1;
    }
  }
  r_nodes_ = static_cast<int>(cols.size() * rows.size());
  coarsening_ = static_cast<double>(scene.nx) * scene.ny / r_nodes_;

  const double half = 0.5 * dx;
  std::map<std::pair<int, int>, std::int32_t> sample_index;  // (h_x, h_y) → sample (fluid points only)
  points_.clear();
  pairs_.clear();
  const auto sample_of = [&](int hx, int hy) -> std::int32_t {
    const Vec2 q(hx * half, hy * half);
    if (scene.is_wall(q.y())) return -1;
    auto [it, fresh] = sample_index.try_emplace({hx, hy}, static_cast<std::int32_t>(points_.size()));
    if (fresh) points_.push_back(q);
    return it->second;
  };
  const auto wrap = [](int h, int n2) { return (h % n2 + n2) % n2; };
  // The lattice rows (height, share) that a point at height h·ε'/2 stands for.
  const auto rows_of = [half](int h) -> std::vector<std::pair<double, double>> {
    if (h % 2 != 0) return {{h * half, 1.0}};
    return {{(h - 1) * half, 0.5}, {(h + 1) * half, 0.5}};
  };
  const double lo = scene.wall_lo, hi = scene.wall_hi;
  const auto wall_distance = [&](double y) { return y < lo ? lo - y : y - hi; };
  std::vector<Vec2> bond_start;  // positions of the a-ends (unwrapped), for the weights
  for (const auto& row : rows)
    for (const auto& col : cols)
      for (const auto& [ox, oy] : offsets) {
        // The virtual pair of (β, ρ_j): from the R-cell centre c to c + ρ_j (midpoint R = c + ρ_j/2; with ±ρ_j
        // the midpoints lie symmetrically about c).
        const int hx = col.centre, hy = row.centre;
        int hx2 = hx + 2 * ox, hy2 = hy + 2 * oy;
        if (hy2 < 0 || hy2 > 2 * scene.ny) {
          if (!scene.box.periodic_y) continue;  // outside the box: no particle there
          hy2 = wrap(hy2, 2 * scene.ny);
        }
        if (hx2 < 0 || hx2 > 2 * scene.nx) {
          if (!scene.box.periodic_x) continue;
          hx2 = wrap(hx2, 2 * scene.nx);
        }
        const Vec2 qa(hx * half, hy * half), qb(hx2 * half, hy2 * half);
        const bool wa = scene.is_wall(qa.y()), wb = scene.is_wall(qb.y());
        if (wa && wb) continue;  // direct SPH has no wall–wall pairs
        VirtualPair p;
        p.sa = sample_of(hx, hy);
        p.sb = sample_of(hx2, hy2);
        p.rho = Vec2(ox * dx, oy * dx);
        const double r = p.rho.norm();
        p.F = w.dw(r) / r;
        // Phase-dependent parts of (5.1) (viscosity, the unlike-pair pressure of (7.1)): an end at a row centre
        // (odd h) stands for that row; an end on a row boundary (even h, where the phase interfaces lie) for
        // half of each neighbouring row, so the pair takes the mean over the row combinations.
        p.mu_ab = 0.0;
        double unlike = 0.0;
        for (const auto& [ya, fa] : rows_of(hy))
          for (const auto& [yb, fb] : rows_of(hy2)) {
            p.mu_ab += fa * fb * pair_viscosity(scene.viscosity_at(Vec2(qa.x(), ya)), scene.viscosity_at(Vec2(qb.x(), yb)),
                                                scene.pair_viscosity_mean);
            unlike += fa * fb * (scene.phase(ya) != scene.phase(yb) ? 1.0 : 0.0);
          }
        p.p_over_n2 = p_over_n2_ + unlike * scene.unlike_pair_excess_over_n2();
        // ½ (N/N_C share) per unit bond integral: ½ s_x × rows; x-integrated: ½ rows / ε' per unit 1D weight.
        p.weight = x_integrated ? 0.5 * row.sites / dx : 0.5 * col.sites * row.sites;
        p.mass = 0.5 * col.sites * row.sites;
        p.beta = 0.0;
        if (scene.wall_model == WallModel::GhostVelocity && wa != wb) {
          const double yw = wa ? qa.y() : qb.y(), yf = wa ? qb.y() : qa.y();
          const bool lower = yw < lo;
          const double d_fluid = std::max(lower ? yf - lo : hi - yf, 1e-3 * dx);
          p.beta = std::min(scene.ghost_beta_max, 1.0 + wall_distance(yw) / d_fluid);
        }
        pairs_.push_back(p);
        bond_start.push_back(qa);
      }

  weight_start_.assign(pairs_.size() + 1, 0);
  weight_node_.clear();
  weight_value_.clear();
  BondWeights bw;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    bw.clear();
    if (x_integrated)
      append_bond_weights_x_integrated(kernel, nodes, bond_start[p].y(), pairs_[p].rho.y(), bw);
    else
      append_bond_weights(kernel, nodes, bond_start[p], pairs_[p].rho, bw);
    for (const auto& [n, b] : bw) {
      weight_node_.push_back(n);
      weight_value_.push_back(pairs_[p].weight * b);
    }
    weight_start_[p + 1] = static_cast<std::int64_t>(weight_node_.size());
  }
  cost_ = QuadratureCost{};
  cost_.bond_weights = static_cast<long>(weight_node_.size());
  cost_.sample_points = static_cast<long>(points_.size());
  cost_.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Eigen::Matrix2Xd CoarseQuadrature::sample(const VelocitySampler& sampler) const {
  if (weight_start_.empty()) throw std::logic_error("coarse quadrature: evaluate before setup");
  const Eigen::Matrix2Xd v = sampler(points_);
  if (v.cols() != static_cast<Eigen::Index>(points_.size()))
    throw NumericalError("coarse quadrature: the velocity sampler returned the wrong number of points");
  if (!v.allFinite()) throw NumericalError("coarse quadrature: non-finite sampled velocity");
  return v;
}

Vec2 CoarseQuadrature::pair_force(const VirtualPair& p, const Eigen::Matrix2Xd& v) const {
  const Vec2 va = p.sa >= 0 ? Vec2(v.col(p.sa)) : Vec2::Zero(), vb = p.sb >= 0 ? Vec2(v.col(p.sb)) : Vec2::Zero();
  Vec2 v_ab = va - vb;
  if (p.beta != 0.0) v_ab = p.sa >= 0 ? Vec2(p.beta * va) : Vec2(-p.beta * vb);  // as SphEngine's ghost wall
  // (5.1) on the a-end due to the b-end; q_ab = q_a − q_b = −ρ.
  return sph_pair_force(p.p_over_n2, p.p_over_n2, p.mu_ab, n_star_, n_star_, p.F, -p.rho, v_ab);
}

std::map<std::string, Eigen::VectorXd> CoarseQuadrature::evaluate(const VelocitySampler& sampler) {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Matrix2Xd v = sample(sampler);
  const int nc = static_cast<int>(comp_index_.size());
  const int nthreads = omp_get_max_threads();
  std::vector<std::vector<double>> acc(nthreads, std::vector<double>(static_cast<std::size_t>(node_count_) * nc, 0.0));
#pragma omp parallel num_threads(nthreads)
  {
    auto& buf = acc[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
      const Vec2 f = pair_force(pairs_[p], v);
      double tab[4];
      for (int c = 0; c < nc; ++c) tab[c] = f[comp_index_[c].first] * pairs_[p].rho[comp_index_[c].second];
      for (std::int64_t e = weight_start_[p]; e < weight_start_[p + 1]; ++e) {
        double* out = &buf[static_cast<std::size_t>(weight_node_[e]) * nc];
        for (int c = 0; c < nc; ++c) out[c] += tab[c] * weight_value_[e];  // (5.27)
      }
    }
  }
  auto out = reduce_node_buffers(acc, node_count_, components_);
  ++cost_.evaluations;
  cost_.pair_forces += static_cast<long>(pairs_.size());
  cost_.evaluate_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

Eigen::Matrix2d CoarseQuadrature::virial(const VelocitySampler& sampler) const {
  const Eigen::Matrix2Xd v = sample(sampler);
  Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
  for (const auto& p : pairs_) s += p.mass * pair_force(p, v) * p.rho.transpose();
  return s;
}

}  // namespace closurelab
