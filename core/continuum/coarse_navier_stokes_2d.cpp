#include "core/continuum/coarse_navier_stokes_2d.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <vector>

#include "core/averaging/averaging.hpp"
#include "core/continuum/periodic_projection_2d.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

namespace {

bool doubly_periodic(const UniformMesh1D& a) {
  return a.periodic && a.count >= 4 && a.spacing > 0.0 && std::abs(a.period - a.count * a.spacing) <= 1e-9 * a.period;
}

}  // namespace

CoarseNavierStokes2D::CoarseNavierStokes2D(TensorMesh2D mesh, double density, double viscosity, Eigen::VectorXd force_x,
                                           Eigen::VectorXd force_y, CoarseNavierStokes2DOptions options)
    : mesh_(std::move(mesh)), rho_(density), nu_(viscosity / density), opt_(options) {
  if (!doubly_periodic(mesh_.x) || !doubly_periodic(mesh_.y))
    throw std::invalid_argument(
        "coarse Navier-Stokes: the mesh must be periodic in x and y with at least 4 nodes "
        "along a side and period = count * spacing");
  if (!(density > 0.0) || !(viscosity > 0.0))
    throw std::invalid_argument("coarse Navier-Stokes: density and viscosity must be positive");
  if (!(opt_.cfl > 0.0) || !(opt_.viscous_number > 0.0) || !(opt_.max_time_step > 0.0))
    throw std::invalid_argument("coarse Navier-Stokes: cfl, viscous_number and max_time_step must be positive");
  const int n = mesh_.size();
  fx_ = force_x.size() == 0 ? Eigen::VectorXd::Zero(n) : std::move(force_x);
  fy_ = force_y.size() == 0 ? Eigen::VectorXd::Zero(n) : std::move(force_y);
  if (fx_.size() != n || fy_.size() != n)
    throw std::invalid_argument("coarse Navier-Stokes: the force must have one value per node");
  projection_ = std::make_unique<PeriodicProjection2D>(
      PeriodicProjection2D::central_symbol(mesh_.nx(), mesh_.x.spacing),
      PeriodicProjection2D::central_symbol(mesh_.ny(), mesh_.y.spacing));
  vx_ = vy_ = p_ = Eigen::VectorXd::Zero(n);
}

CoarseNavierStokes2D::~CoarseNavierStokes2D() = default;

void CoarseNavierStokes2D::project(Eigen::VectorXd& vx, Eigen::VectorXd& vy, double dt) {
  if (dt > 0.0) {  // the pressure ρ φ / Δt of the removed gradient
    projection_->project(vx, vy, &p_);
    p_ *= rho_ / dt;
  } else {
    projection_->project(vx, vy);
  }
}

double CoarseNavierStokes2D::set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) {
  if (vx.size() != mesh_.size() || vy.size() != mesh_.size())
    throw std::invalid_argument("coarse Navier-Stokes: the velocity must have one value per node");
  vx_ = vx;
  vy_ = vy;
  project(vx_, vy_, 0.0);
  time_ = 0.0;
  steps_ = 0;
  dt_prev_ = 0.0;
  p_.setZero();
  double removed = 0.0;
  for (int n = 0; n < mesh_.size(); ++n) removed = std::max(removed, std::hypot(vx[n] - vx_[n], vy[n] - vy_[n]));
  return removed;
}

void CoarseNavierStokes2D::unprojected_rate(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy, Eigen::VectorXd& rx,
                                            Eigen::VectorXd& ry) const {
  const int nx = mesh_.nx(), ny = mesh_.ny();
  const double hx = mesh_.x.spacing, hy = mesh_.y.spacing;
  const double cx = 0.5 / hx, cy = 0.5 / hy, lx = nu_ / (hx * hx), ly = nu_ / (hy * hy);
  rx.resize(mesh_.size());
  ry.resize(mesh_.size());
  for (int j = 0; j < ny; ++j) {
    const int jp = (j + 1) % ny, jm = (j + ny - 1) % ny;
    for (int i = 0; i < nx; ++i) {
      const int ip = (i + 1) % nx, im = (i + nx - 1) % nx;
      const int c = j * nx + i, e = j * nx + ip, w = j * nx + im, no = jp * nx + i, so = jm * nx + i;
      // ∇·(v ⊗ v): ∂_x (v_x v_a) + ∂_y (v_y v_a), central differences of the products.
      const double conv_x = cx * (vx[e] * vx[e] - vx[w] * vx[w]) + cy * (vy[no] * vx[no] - vy[so] * vx[so]);
      const double conv_y = cx * (vx[e] * vy[e] - vx[w] * vy[w]) + cy * (vy[no] * vy[no] - vy[so] * vy[so]);
      const double lap_x = lx * (vx[e] - 2.0 * vx[c] + vx[w]) + ly * (vx[no] - 2.0 * vx[c] + vx[so]);
      const double lap_y = lx * (vy[e] - 2.0 * vy[c] + vy[w]) + ly * (vy[no] - 2.0 * vy[c] + vy[so]);
      rx[c] = -conv_x + lap_x + fx_[c];
      ry[c] = -conv_y + lap_y + fy_[c];
    }
  }
}

bool CoarseNavierStokes2D::step(double dt) {
  Eigen::VectorXd rx, ry;
  unprojected_rate(vx_, vy_, rx, ry);
  Eigen::VectorXd nx = ab2(vx_, rx, rx_prev_, dt, dt_prev_), ny = ab2(vy_, ry, ry_prev_, dt, dt_prev_);
  const Eigen::VectorXd p_before = p_;
  project(nx, ny, dt);
  if (!nx.allFinite() || !ny.allFinite()) {
    p_ = p_before;
    return false;
  }
  vx_ = std::move(nx);
  vy_ = std::move(ny);
  rx_prev_ = std::move(rx);
  ry_prev_ = std::move(ry);
  dt_prev_ = dt;
  time_ += dt;
  ++steps_;
  return true;
}

double CoarseNavierStokes2D::time_step() const {
  const double h = std::min(mesh_.x.spacing, mesh_.y.spacing);
  double vmax = 0.0;
  for (int n = 0; n < mesh_.size(); ++n) vmax = std::max(vmax, std::hypot(vx_[n], vy_[n]));
  double dt = std::min(opt_.max_time_step, opt_.viscous_number * h * h / nu_);
  if (vmax > 0.0) dt = std::min(dt, opt_.cfl * h / vmax);
  return dt;
}

Eigen::VectorXd CoarseNavierStokes2D::divergence() const {
  const int nx = mesh_.nx(), ny = mesh_.ny();
  const double cx = 0.5 / mesh_.x.spacing, cy = 0.5 / mesh_.y.spacing;
  Eigen::VectorXd d(mesh_.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      d[j * nx + i] = cx * (vx_[j * nx + (i + 1) % nx] - vx_[j * nx + (i + nx - 1) % nx]) +
                      cy * (vy_[((j + 1) % ny) * nx + i] - vy_[((j + ny - 1) % ny) * nx + i]);
  return d;
}

Eigen::Vector2d CoarseNavierStokes2D::velocity_at(double x, double y) const {
  const int nx = mesh_.nx(), ny = mesh_.ny();
  const double sx = (x - mesh_.x.origin) / mesh_.x.spacing, sy = (y - mesh_.y.origin) / mesh_.y.spacing;
  const double fx = std::floor(sx), fy = std::floor(sy), a = sx - fx, b = sy - fy;
  const int i0 = ((static_cast<long>(fx) % nx) + nx) % nx, j0 = ((static_cast<long>(fy) % ny) + ny) % ny;
  const int i1 = (i0 + 1) % nx, j1 = (j0 + 1) % ny;
  const auto at = [&](const Eigen::VectorXd& f) {
    return (1 - a) * (1 - b) * f[j0 * nx + i0] + a * (1 - b) * f[j0 * nx + i1] + (1 - a) * b * f[j1 * nx + i0] +
           a * b * f[j1 * nx + i1];
  };
  return {at(vx_), at(vy_)};
}

double CoarseNavierStokes2D::laplacian_eigenvalue(double kx, double ky) const {
  const double hx = mesh_.x.spacing, hy = mesh_.y.spacing;
  const double sx = std::sin(0.5 * kx * hx), sy = std::sin(0.5 * ky * hy);
  return -4.0 * (sx * sx / (hx * hx) + sy * sy / (hy * hy));
}

void sampled_body_force(const Scene& scene, const TensorMesh2D& mesh, Eigen::VectorXd& fx, Eigen::VectorXd& fy) {
  fx = fy = Eigen::VectorXd::Zero(mesh.size());
  for (int n = 0; n < mesh.size(); ++n) {
    const Vec2 q = mesh.node(n);
    if (scene.body_force) {
      const Vec2 f = scene.body_force(q.x(), q.y());
      fx[n] = f.x();
      fy[n] = f.y();
    } else if (scene.force_x) {
      fx[n] = scene.force_x(q.y());
    }
  }
}

void averaged_body_force(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh,
                         Eigen::VectorXd& fx, Eigen::VectorXd& fy, Eigen::VectorXd* density) {
  ParticleSystem lattice = scene.make_particles();
  for (std::size_t a = 0; a < lattice.size(); ++a) {
    const Vec2 f = scene.body_force ? scene.body_force(lattice.x[a], lattice.y[a])
                                    : Vec2(scene.force_x ? scene.force_x(lattice.y[a]) : 0.0, 0.0);
    lattice.vx[a] = f.x();
    lattice.vy[a] = f.y();
  }
  const MesoFields f = average_particles(lattice, scene.box, kernel, mesh, AveragingRequest{});
  fx = f.vx;
  fy = f.vy;
  if (density) *density = f.rho;
}

std::unique_ptr<CoarseNavierStokes2D> coarse_navier_stokes_for(const Scene& scene, const TensorMesh2D& mesh,
                                                               CoarseNavierStokes2DOptions options,
                                                               const AveragingKernel* average_force) {
  if (scene.has_walls || !scene.box.periodic_x || !scene.box.periodic_y || scene.solid_at ||
      scene.phase_viscosity.size() != 1)
    throw std::invalid_argument(
        "the coarse continuum baseline needs a doubly periodic box of one phase without walls "
        "or solids; scene '" +
        scene.name + "' is not one");
  Eigen::VectorXd fx, fy;
  if (average_force)
    averaged_body_force(scene, *average_force, mesh, fx, fy);
  else
    sampled_body_force(scene, mesh, fx, fy);
  return std::make_unique<CoarseNavierStokes2D>(mesh, scene.rho0, scene.phase_viscosity[0], std::move(fx),
                                                std::move(fy), options);
}

}  // namespace closurelab
