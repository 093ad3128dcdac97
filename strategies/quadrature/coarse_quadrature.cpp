#include "strategies/quadrature/coarse_quadrature.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <map>
#include <stdexcept>

#include "core/averaging/averaging.hpp"
#include "core/averaging/bond_weights.hpp"
#include "core/base/errors.hpp"
#include "core/base/periodic_fft_2d.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab {

namespace {

std::string divisors_of(int n) {
  std::string s;
  for (int d = 1; d <= n; ++d)
    if (n % d == 0) s += (s.empty() ? "" : ", ") + std::to_string(d);
  return s;
}

}  // namespace

using Complex = std::complex<double>;

// Per offset j, the DFT of its bond-weight stencil about R-cell 0 on the node mesh.
struct CoarseQuadrature::Convolution {
  PeriodicFft2D fft;
  std::vector<std::vector<Complex>> stencil_hat;  // [j][node]
  std::vector<Complex> z, row_x, row_y;           // work: one offset's forces; Σ_j over bond rows b = x, y
  Convolution(int nx, int ny) : fft(nx, ny) {}
};

CoarseQuadrature::CoarseQuadrature(int stride_x, int stride_y, bool refine_walls, bool convolution)
    : stride_x_(stride_x), stride_y_(stride_y), refine_walls_(refine_walls), use_convolution_(convolution) {
  if (stride_x < 0) throw ConfigError("/stride_x", "must be >= 0 (0: x-integrated, for x-invariant scenes)");
  if (stride_y < 1) throw ConfigError("/stride_y", "must be >= 1");
}

CoarseQuadrature::~CoarseQuadrature() = default;

void CoarseQuadrature::check(const Scene& scene, const TensorMesh2D& nodes,
                             const std::vector<std::string>& components) const {
  // Walls are known to it in y only (has_walls): solids given by position (the cavity's walls and lid, the
  // cylinders) would be sampled as fluid and their pairs kept.
  if (scene.solid_at)
    throw ConfigError("", "the coarse quadrature knows walls in y only; scene '" + scene.name +
                              "' has solids given by position (walls of a box, cylinders), whose sites it would "
                              "sample as fluid: use the exact quadrature");
  // The R-grid must tile the lattice: N/N_C = s_x s_y with whole blocks of sites.
  if (scene.ny % stride_y_ != 0)
    throw ConfigError("/stride_y", "the R-grid stride " + std::to_string(stride_y_) +
                                       " does not divide the lattice's n_y = " + std::to_string(scene.ny) +
                                       "; allowed strides: " + divisors_of(scene.ny));
  if (stride_x_ == 0 && !scene.x_invariant)
    throw ConfigError("/stride_x", "0 (x-integrated R-grid) needs an x-invariant scene; scene '" + scene.name +
                                       "' is not: give a stride dividing n_x = " + std::to_string(scene.nx));
  if (stride_x_ != 0 && scene.nx % stride_x_ != 0)
    throw ConfigError("/stride_x", "the R-grid stride " + std::to_string(stride_x_) +
                                       " does not divide the lattice's n_x = " + std::to_string(scene.nx) +
                                       "; allowed strides: " + divisors_of(scene.nx) +
                                       (scene.x_invariant ? " (or 0: x-integrated)" : ""));
  check_mesh_matches_box(nodes, scene.box);
  component_indices(components);
}

// Positions in half lattice units: h ↦ h ε'/2, so lattice site i sits at h = 2i + 1 and the centre of a run
// of L sites starting at i0 at h = 2 i0 + L (a site when L is odd, between two when L is even).
CoarseQuadrature::RGrid CoarseQuadrature::r_grid(const Scene& scene) const {
  RGrid g;
  const int sx = stride_x_ == 0 ? scene.nx : stride_x_, sy = stride_y_;
  if (stride_x_ == 0)
    g.cols = {{1, scene.nx}};  // one column per strip period (x-integrated weights)
  else
    for (int m = 0; m < scene.nx / sx; ++m) g.cols.push_back({2 * m * sx + sx, sx});
  // R-rows: the centres of blocks of s_y rows (the coarse cells' centres q_β). With refined wall bands, rows
  // within one SPH support of a wall surface (where bonds straddle the wall and the integrand of (5.25)
  // jumps) are R-rows of their own, and each contiguous rest of a block is one R-row at its centre.
  const double rs = scene.smoothing_kernel().support();
  const auto near_wall = [&](int j) {
    const double y = (j + 0.5) * scene.dx;
    return refine_walls_ && scene.has_walls && (std::abs(y - scene.wall_lo) < rs || std::abs(y - scene.wall_hi) < rs);
  };
  for (int m = 0; m < scene.ny / sy; ++m) {
    int start = m * sy;
    for (int j = m * sy; j <= (m + 1) * sy; ++j) {
      const bool end = j == (m + 1) * sy;
      if (!end && !near_wall(j)) continue;
      if (j > start) g.rows.push_back({2 * start + (j - start), j - start});
      if (!end) g.rows.push_back({2 * j + 1, 1});
      start = j + 1;
    }
  }
  return g;
}

// The phase-dependent parts of (5.1) (viscosity, the unlike-pair pressure of (7.1)) and the ghost-wall factor of
// the virtual pair from half-unit heights ha to hb (qa, qb its ends).
void CoarseQuadrature::set_pair_physics(const Scene& scene, int ha, int hb, const Vec2& qa, const Vec2& qb,
                                        VirtualPair& p) const {
  const double half = 0.5 * scene.dx;
  // An end at a row centre (odd h) stands for that row; an end on a row boundary (even h, where the phase
  // interfaces lie) for half of each neighbouring row, so the pair takes the mean over the row combinations.
  const auto rows_of = [half](int h) -> std::vector<std::pair<double, double>> {
    if (h % 2 != 0) return {{h * half, 1.0}};
    return {{(h - 1) * half, 0.5}, {(h + 1) * half, 0.5}};
  };
  p.mu_ab = 0.0;
  double unlike = 0.0;
  for (const auto& [ya, fa] : rows_of(ha))
    for (const auto& [yb, fb] : rows_of(hb)) {
      p.mu_ab += fa * fb *
                 pair_viscosity(scene.viscosity_at(Vec2(qa.x(), ya)), scene.viscosity_at(Vec2(qb.x(), yb)),
                                scene.pair_viscosity_mean);
      unlike += fa * fb * (scene.phase(ya) != scene.phase(yb) ? 1.0 : 0.0);
    }
  p.p_over_n2 = p_over_n2_ + unlike * scene.unlike_pair_excess_over_n2();
  p.beta = 0.0;
  const bool wa = scene.is_wall(qa.y()), wb = scene.is_wall(qb.y());
  if (scene.wall_model == WallModel::ghost_velocity && wa != wb) {
    const double lo = scene.wall_lo, hi = scene.wall_hi;
    const double yw = wa ? qa.y() : qb.y(), yf = wa ? qb.y() : qa.y();
    const bool lower = yw < lo;
    const double d_fluid = std::max(lower ? yf - lo : hi - yf, 1e-3 * scene.dx);
    p.beta = std::min(scene.ghost_beta_max, 1.0 + (yw < lo ? lo - yw : yw - hi) / d_fluid);
  }
}

void CoarseQuadrature::setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
                             const std::vector<std::string>& components) {
  const auto t0 = std::chrono::steady_clock::now();
  check(scene, nodes, components);
  const bool x_integrated = stride_x_ == 0;
  const SmoothingKernel w = scene.smoothing_kernel();
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
  const RGrid grid = r_grid(scene);
  r_nodes_ = static_cast<int>(grid.cols.size() * grid.rows.size());
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
  std::vector<Vec2> bond_start;  // positions of the a-ends (unwrapped), for the weights
  for (const auto& row : grid.rows)
    for (const auto& col : grid.cols)
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
        if (scene.is_wall(qa.y()) && scene.is_wall(qb.y())) continue;  // direct SPH has no wall–wall pairs
        VirtualPair p;
        p.sa = sample_of(hx, hy);
        p.sb = sample_of(hx2, hy2);
        p.rho = Vec2(ox * dx, oy * dx);
        const double r = p.rho.norm();
        p.F = w.dw(r) / r;
        set_pair_physics(scene, hy, hy2, qa, qb, p);
        // ½ (N/N_C share) per unit bond integral: ½ s_x × rows; x-integrated: ½ rows / ε' per unit 1D weight.
        p.weight = x_integrated ? 0.5 * row.sites / dx : 0.5 * col.sites * row.sites;
        p.mass = 0.5 * col.sites * row.sites;
        pairs_.push_back(p);
        bond_start.push_back(qa);
      }

  cost_ = QuadratureCost{};
  convolution_.reset();
  weights_ = BondWeightTable{};
  components_ = components;
  if (use_convolution_ && translation_invariant(scene, nodes, grid)) {
    // The stencils of R-cell 0 (pairs 0 .. J − 1), transformed once.
    convolution_ = std::make_unique<Convolution>(nodes.nx(), nodes.ny());
    convolution_->stencil_hat.resize(static_cast<std::size_t>(offsets_));
    BondWeights bw;
    for (int j = 0; j < offsets_; ++j) {
      bw.clear();
      append_bond_weights(kernel, nodes, bond_start[j], pairs_[j].rho, bw);
      std::vector<Complex>& w = convolution_->stencil_hat[j];
      w.assign(static_cast<std::size_t>(nodes.size()), Complex(0.0, 0.0));
      for (const auto& [node, b] : bw) w[static_cast<std::size_t>(node)] += b * pairs_[j].weight;
      cost_.bond_weights += static_cast<long>(bw.size());
      convolution_->fft.forward(w);
    }
  } else {
    weights_.tabulate(pairs_.size(), nodes.size(), components, [&](std::size_t p, BondWeights& bw) {
      if (x_integrated)
        append_bond_weights_x_integrated(kernel, nodes, bond_start[p].y(), pairs_[p].rho.y(), bw);
      else
        append_bond_weights(kernel, nodes, bond_start[p], pairs_[p].rho, bw);
      for (auto& entry : bw) entry.second *= pairs_[p].weight;
    });
    cost_.bond_weights = weights_.entries();
  }
  set_up_ = true;
  cost_.sample_points = static_cast<long>(points_.size());
  cost_.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Eigen::Matrix2Xd CoarseQuadrature::sample(const VelocitySampler& sampler) const {
  if (!set_up_) throw std::logic_error("coarse quadrature: evaluate before setup");
  const Eigen::Matrix2Xd v = sampler(points_);
  if (v.cols() != static_cast<Eigen::Index>(points_.size()))
    throw std::logic_error("coarse quadrature: the velocity sampler returned the wrong number of points");
  return v;
}

Vec2 CoarseQuadrature::pair_force(const VirtualPair& p, const Eigen::Matrix2Xd& v) const {
  const Vec2 va = p.sa >= 0 ? Vec2(v.col(p.sa)) : Vec2::Zero(), vb = p.sb >= 0 ? Vec2(v.col(p.sb)) : Vec2::Zero();
  Vec2 v_ab = va - vb;
  if (p.beta != 0.0) v_ab = p.sa >= 0 ? Vec2(p.beta * va) : Vec2(-p.beta * vb);  // as SphEngine's ghost wall
  // (5.1) on the a-end due to the b-end; q_ab = q_a − q_b = −ρ.
  return sph_pair_force(p.p_over_n2, p.p_over_n2, p.mu_ab, n_star_, n_star_, p.F, -p.rho, v_ab);
}

QuadratureResult CoarseQuadrature::evaluate(const VelocitySampler& sampler) {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Matrix2Xd v = sample(sampler);
  QuadratureResult r;
  if (!v.allFinite()) {
    r.status = Status::numerical_issue;
    r.message = "coarse quadrature: non-finite sampled velocity";
    return r;
  }
  if (convolution_)
    r.stress = convolve(v);
  else
    r.stress =
        weights_.accumulate([&](std::size_t p) { return std::make_pair(pair_force(pairs_[p], v), pairs_[p].rho); });
  r.pair_forces = static_cast<long>(pairs_.size());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finite_or_issue(std::move(r), "coarse quadrature");
}

bool CoarseQuadrature::translation_invariant(const Scene& scene, const TensorMesh2D& nodes, const RGrid& grid) const {
  if (stride_x_ == 0 || scene.has_walls || !scene.box.periodic_x || !scene.box.periodic_y || !nodes.x.periodic ||
      !nodes.y.periodic)
    return false;
  // One R-cell per node, the R-grid's spacings the node spacings: shifting by an R-cell shifts by a node.
  const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); };
  if (static_cast<int>(grid.cols.size()) != nodes.nx() || static_cast<int>(grid.rows.size()) != nodes.ny() ||
      !same(nodes.x.spacing, stride_x_ * scene.dx) || !same(nodes.y.spacing, stride_y_ * scene.dx))
    return false;
  // Every R-cell carries the same pairs with the same physics (one phase, no wall ends).
  const std::size_t J = static_cast<std::size_t>(offsets_);
  if (pairs_.size() != J * static_cast<std::size_t>(r_nodes_)) return false;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const VirtualPair &a = pairs_[p], &b = pairs_[p % J];
    if (a.sa < 0 || a.sb < 0 || a.beta != 0.0 || a.rho != b.rho || a.F != b.F || a.mu_ab != b.mu_ab ||
        a.p_over_n2 != b.p_over_n2 || a.weight != b.weight)
      return false;
  }
  return true;
}

std::map<std::string, Eigen::VectorXd> CoarseQuadrature::convolve(const Eigen::Matrix2Xd& v) {
  Convolution& c = *convolution_;
  const std::size_t nodes = c.stencil_hat.empty() ? 0 : c.stencil_hat[0].size(), J = c.stencil_hat.size();
  c.row_x.assign(nodes, Complex(0.0, 0.0));
  c.row_y.assign(nodes, Complex(0.0, 0.0));
  c.z.resize(nodes);
  for (std::size_t j = 0; j < J; ++j) {
    // Pair (β, j) is pairs_[β J + j], β the R-cell's flat index, which is its node's.
    for (std::size_t b = 0; b < nodes; ++b) {
      const Vec2 f = pair_force(pairs_[b * J + j], v);
      c.z[b] = Complex(f.x(), f.y());
    }
    c.fft.forward(c.z);
    const Vec2& rho = pairs_[j].rho;
    const std::vector<Complex>& w = c.stencil_hat[j];
    for (std::size_t k = 0; k < nodes; ++k) {
      const Complex fw = c.z[k] * w[k];
      c.row_x[k] += rho.x() * fw;
      c.row_y[k] += rho.y() * fw;
    }
  }
  c.fft.inverse(c.row_x);  // T_xx + i T_yx
  c.fft.inverse(c.row_y);  // T_xy + i T_yy
  std::map<std::string, Eigen::VectorXd> out;
  for (const auto& name : components_) {
    const auto [a, b] = component_index(name);
    const std::vector<Complex>& row = b == 0 ? c.row_x : c.row_y;
    Eigen::VectorXd t(static_cast<Eigen::Index>(nodes));
    for (std::size_t k = 0; k < nodes; ++k) t[static_cast<Eigen::Index>(k)] = a == 0 ? row[k].real() : row[k].imag();
    out[name] = std::move(t);
  }
  return out;
}

Eigen::Matrix2d CoarseQuadrature::virial(const VelocitySampler& sampler) const {
  const Eigen::Matrix2Xd v = sample(sampler);
  Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
  for (const auto& p : pairs_) s += p.mass * pair_force(p, v) * p.rho.transpose();
  return s;
}

}  // namespace closurelab
