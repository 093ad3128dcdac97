#include "core/reduced/walled_box_2d.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/sph/particles.hpp"
#include "core/sph/sph_engine.hpp"

namespace closurelab {

TensorMesh2D walled_faces_of(const TensorMesh2D& c, int axis) {
  TensorMesh2D f = c;
  UniformMesh1D& a = axis == 0 ? f.x : f.y;
  a.origin -= 0.5 * a.spacing;  // i Δ from the wall: face i is the left (lower) face of cell i, face n the far wall
  a.count += 1;
  a.periodic = false;
  return f;
}

namespace {

// The cell (i, j) of `cells` and its neighbours along `axis`, as (along, across) with the faces' flat index.
struct AxisView {
  int n, m;  // cells along the axis, across it
  bool x;    // axis 0
  int cell(int along, int across) const { return x ? across * n + along : along * m + across; }
  int face(int along, int across) const { return x ? across * (n + 1) + along : along * m + across; }
};

AxisView view_of(const TensorMesh2D& c, int axis) {
  return axis == 0 ? AxisView{c.nx(), c.ny(), true} : AxisView{c.ny(), c.nx(), false};
}

}  // namespace

Eigen::VectorXd walled_face_difference(const TensorMesh2D& cells, const Eigen::VectorXd& f, int axis, int order) {
  const AxisView v = view_of(cells, axis);
  const double h = axis == 0 ? cells.x.spacing : cells.y.spacing;
  Eigen::VectorXd out(cells.size());
  for (int b = 0; b < v.m; ++b)
    for (int a = 0; a < v.n; ++a) {
      const double inner = f[v.face(a + 1, b)] - f[v.face(a, b)];
      const bool wide = order == 4 && a >= 1 && a + 2 <= v.n;
      out[v.cell(a, b)] = wide ? (27.0 * inner - (f[v.face(a + 2, b)] - f[v.face(a - 1, b)])) / (24.0 * h) : inner / h;
    }
  return out;
}

Eigen::VectorXd walled_to_faces(const TensorMesh2D& cells, const Eigen::VectorXd& c, int axis, int order) {
  const AxisView v = view_of(cells, axis);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(v.n + 1) * v.m);
  for (int b = 0; b < v.m; ++b)
    for (int a = 1; a < v.n; ++a) {  // face a lies between cells a − 1 and a; faces 0 and n are the walls
      const double inner = c[v.cell(a - 1, b)] + c[v.cell(a, b)];
      const bool wide = order == 4 && a >= 2 && a + 1 < v.n;
      out[v.face(a, b)] = wide ? (9.0 * inner - (c[v.cell(a - 2, b)] + c[v.cell(a + 1, b)])) / 16.0 : 0.5 * inner;
    }
  return out;
}

WalledProjection2D::WalledProjection2D(const TensorMesh2D& cells, int order) : cells_(cells), order_(order) {
  if (cells.nx() > kMaxWalledProjectionSide || cells.ny() > kMaxWalledProjectionSide)
    throw ConfigError("/solver/spacing_over_eta", "the walled projection is dense and takes at most " +
                                                      std::to_string(kMaxWalledProjectionSide) +
                                                      " cells along a side; this mesh has " +
                                                      std::to_string(cells.nx()) + " x " + std::to_string(cells.ny()));
  const Eigen::Index n = cells.size();
  // D and Dᵀ (2n² each), D Dᵀ, its eigenvectors and the pseudo-inverse (n² each), at once.
  check_allocation(7.0 * static_cast<double>(n) * static_cast<double>(n), sizeof(double),
                   "the walled projection's dense matrices", "/solver/spacing_over_eta");
  Eigen::MatrixXd d(n, 2 * n);  // column by column: D applied to unit vectors
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, k);
    d.col(k) = divergence(e, zero);
    d.col(n + k) = divergence(zero, e);
  }
  dt_ = d.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(d * dt_);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const double cut = 1e-12 * lambda.cwiseAbs().maxCoeff();
  Eigen::VectorXd inv(n);
  for (Eigen::Index k = 0; k < n; ++k) inv[k] = lambda[k] > cut ? 1.0 / lambda[k] : 0.0;
  pinv_ = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::VectorXd WalledProjection2D::divergence(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) const {
  return walled_face_difference(cells_, walled_to_faces(cells_, vx, 0, order_), 0, order_) +
         walled_face_difference(cells_, walled_to_faces(cells_, vy, 1, order_), 1, order_);
}

void WalledProjection2D::project(Eigen::VectorXd& vx, Eigen::VectorXd& vy) const {
  const Eigen::Index n = cells_.size();
  const Eigen::VectorXd g = dt_ * (pinv_ * divergence(vx, vy));
  vx -= g.head(n);
  vy -= g.tail(n);
}

Eigen::VectorXd WalledAveraging::fluid_data(const Eigen::VectorXd& v, int component) const {
  return scale.cwiseProduct(v) - (component == 0 ? wall_x : wall_y);
}

WalledAveraging walled_averaging(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& coarse) {
  if (!scene.cavity) throw ConfigError("/scene", "scene '" + scene.name + "' is not a walled rectangle (the cavity)");
  const Scene::LidDrivenCavity& c = *scene.cavity;
  const int n = static_cast<int>(std::lround(c.side / scene.dx));
  const UniformMesh1D fluid = UniformMesh1D::cell_centred(c.origin, c.side, n, false);
  WalledAveraging w{{fluid, fluid},
                    Eigen::VectorXd::Zero(coarse.size()),
                    Eigen::VectorXd::Zero(coarse.size()),
                    Eigen::VectorXd::Zero(coarse.size())};
  const ParticleSystem ps = scene.make_particles();
  const double cell = scene.dx * scene.dx, reach = kernel.support_radius();
  for (std::size_t a = 0; a < ps.size(); ++a)
    for (int i = 0; i < coarse.size(); ++i) {
      const Vec2 r = coarse.node(i) - Vec2(ps.x[a], ps.y[a]);
      if (std::abs(r.x()) > reach || std::abs(r.y()) > reach) continue;
      const double psi = cell * kernel.value(r);
      w.scale[i] += psi;
      if (ps.fixed[a]) {
        w.wall_x[i] += psi * ps.vx[a];
        w.wall_y[i] += psi * ps.vy[a];
      }
    }
  return w;
}

FluidConvectiveFlux::FluidConvectiveFlux(const AveragingKernel& kernel, const TensorMesh2D& coarse,
                                         const TensorMesh2D& fluid_lattice, double rho0)
    : to_x_faces_(
          make_averaging_operator_2d(kernel, walled_faces_of(coarse, 0), fluid_lattice, Discretization::coarse_fine)),
      to_y_faces_(
          make_averaging_operator_2d(kernel, walled_faces_of(coarse, 1), fluid_lattice, Discretization::coarse_fine)),
      rho0_(rho0) {}

FluidConvectiveFlux::OnFaces FluidConvectiveFlux::evaluate(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) const {
  const Eigen::VectorXd xx = vx.cwiseProduct(vx), xy = vx.cwiseProduct(vy), yy = vy.cwiseProduct(vy);
  return {rho0_ * to_x_faces_.apply(xx), rho0_ * to_x_faces_.apply(xy), rho0_ * to_y_faces_.apply(xy),
          rho0_ * to_y_faces_.apply(yy)};
}

WallConstraintForces2D::WallConstraintForces2D(const Scene& scene, const AveragingKernel& kernel,
                                               const TensorMesh2D& coarse)
    : scene_(std::make_unique<Scene>(scene)), ps_(std::make_unique<ParticleSystem>(scene_->make_particles())) {
  engine_ = std::make_unique<SphEngine>(*scene_, *ps_);
  const double reach = kernel.support_radius();
  wall_column_.assign(ps_->size(), -1);
  std::vector<Eigen::Triplet<double>> entries;
  int walls = 0;
  for (std::size_t a = 0; a < ps_->size(); ++a) {
    if (!ps_->fixed[a]) {
      moving_.push_back(static_cast<std::int32_t>(a));
      moving_points_.emplace_back(ps_->x[a], ps_->y[a]);
      continue;
    }
    bool used = false;
    for (int i = 0; i < coarse.size(); ++i) {
      const Vec2 r = coarse.node(i) - Vec2(ps_->x[a], ps_->y[a]);
      if (std::abs(r.x()) > reach || std::abs(r.y()) > reach) continue;
      entries.emplace_back(i, walls, kernel.value(r));
      used = true;
    }
    if (used) wall_column_[a] = walls++;
  }
  weights_.resize(coarse.size(), walls);
  weights_.setFromTriplets(entries.begin(), entries.end());
}

WallConstraintForces2D::~WallConstraintForces2D() = default;

bool WallConstraintForces2D::evaluate(const VelocitySampler& sampler, Eigen::VectorXd& fx, Eigen::VectorXd& fy,
                                      std::string& issue) {
  const Eigen::Matrix2Xd v = sampler(moving_points_);
  if (!v.allFinite()) {
    issue = "wall constraint forces: non-finite sampled velocity";
    return false;
  }
  for (std::size_t k = 0; k < moving_.size(); ++k) {
    ps_->vx[moving_[k]] = v(0, static_cast<Eigen::Index>(k));
    ps_->vy[moving_[k]] = v(1, static_cast<Eigen::Index>(k));
  }
  Eigen::VectorXd on_x = Eigen::VectorXd::Zero(weights_.cols()), on_y = Eigen::VectorXd::Zero(weights_.cols());
  const std::vector<PairForce> pairs = engine_->pair_forces();  // f on j by k; −f on k
  for (const PairForce& p : pairs) {
    if (const int cj = wall_column_[p.j]; cj >= 0) {
      on_x[cj] += p.f.x();
      on_y[cj] += p.f.y();
    }
    if (const int ck = wall_column_[p.k]; ck >= 0) {
      on_x[ck] -= p.f.x();
      on_y[ck] -= p.f.y();
    }
  }
  pair_forces_ += static_cast<long>(pairs.size());
  fx = -(weights_ * on_x);
  fy = -(weights_ * on_y);
  return true;
}

}  // namespace closurelab
