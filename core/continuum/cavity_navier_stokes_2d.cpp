#include "core/continuum/cavity_navier_stokes_2d.hpp"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace closurelab {

namespace {

bool walled_axis(const UniformMesh1D& a) { return !a.periodic && a.count >= 4 && a.spacing > 0.0; }

}  // namespace

CavityNavierStokes2D::CavityNavierStokes2D(TensorMesh2D mesh, double density, double viscosity, double lid_speed,
                                           CoarseNavierStokes2DOptions options)
    : mesh_(std::move(mesh)),
      nx_(mesh_.nx()),
      ny_(mesh_.ny()),
      hx_(mesh_.x.spacing),
      hy_(mesh_.y.spacing),
      rho_(density),
      nu_(viscosity / density),
      lid_(lid_speed),
      opt_(options) {
  if (!walled_axis(mesh_.x) || !walled_axis(mesh_.y))
    throw std::invalid_argument(
        "cavity Navier-Stokes: the mesh must be periodic in neither direction, with at least 4 "
        "cells along a side");
  if (!(density > 0.0) || !(viscosity > 0.0) || !std::isfinite(lid_speed))
    throw std::invalid_argument("cavity Navier-Stokes: density and viscosity must be positive, the lid speed finite");
  if (!(opt_.cfl > 0.0) || !(opt_.viscous_number > 0.0) || !(opt_.max_time_step > 0.0))
    throw std::invalid_argument("cavity Navier-Stokes: cfl, viscous_number and max_time_step must be positive");
  // −D G on the cells: for each pair of neighbouring cells a and b (an interior face of spacing h),
  // (φ_a − φ_b)/h² added to row a and row b's mirror; cell 0 is pinned (its row and column left out).
  const int cells = nx_ * ny_;
  std::vector<Eigen::Triplet<double>> t;
  const auto pair = [&](int a, int b, double w) {
    if (a > 0) t.emplace_back(a - 1, a - 1, w);
    if (b > 0) t.emplace_back(b - 1, b - 1, w);
    if (a > 0 && b > 0) {
      t.emplace_back(a - 1, b - 1, -w);
      t.emplace_back(b - 1, a - 1, -w);
    }
  };
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      if (i + 1 < nx_) pair(j * nx_ + i, j * nx_ + i + 1, 1.0 / (hx_ * hx_));
      if (j + 1 < ny_) pair(j * nx_ + i, (j + 1) * nx_ + i, 1.0 / (hy_ * hy_));
    }
  Eigen::SparseMatrix<double> a(cells - 1, cells - 1);
  a.setFromTriplets(t.begin(), t.end());
  poisson_.compute(a);
  if (poisson_.info() != Eigen::Success)
    throw std::runtime_error("cavity Navier-Stokes: the Poisson factorization failed");
  u_ = Eigen::VectorXd::Zero((nx_ + 1) * ny_);
  v_ = Eigen::VectorXd::Zero(nx_ * (ny_ + 1));
  p_ = Eigen::VectorXd::Zero(cells);
  update_nodes();
}

double CavityNavierStokes2D::u_at(const Eigen::VectorXd& u, int i, int j) const {
  if (j < 0) return -u[i];                                         // ghost below the bottom wall (at rest)
  if (j >= ny_) return 2.0 * lid_ - u[(ny_ - 1) * (nx_ + 1) + i];  // ghost above the lid
  return u[j * (nx_ + 1) + i];
}

double CavityNavierStokes2D::v_at(const Eigen::VectorXd& v, int i, int j) const {
  if (i < 0) return -v[j * nx_];               // ghost left of the left wall
  if (i >= nx_) return -v[j * nx_ + nx_ - 1];  // ghost right of the right wall
  return v[j * nx_ + i];
}

void CavityNavierStokes2D::rate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& ru,
                                Eigen::VectorXd& rv) const {
  ru = Eigen::VectorXd::Zero(u.size());
  rv = Eigen::VectorXd::Zero(v.size());
  const double lx = nu_ / (hx_ * hx_), ly = nu_ / (hy_ * hy_);
  const auto vf = [&](int i, int j) { return v[j * nx_ + i]; };  // v_y on a face inside the side walls
  for (int j = 0; j < ny_; ++j)
    for (int i = 1; i < nx_; ++i) {  // the interior vertical faces
      const double c = u_at(u, i, j);
      const double ue = 0.5 * (c + u_at(u, i + 1, j)), uw = 0.5 * (u_at(u, i - 1, j) + c);
      // The cross flux v_x v_y at the corners (i, j + 1) and (i, j).
      const double un = 0.5 * (c + u_at(u, i, j + 1)), vn = 0.5 * (vf(i - 1, j + 1) + vf(i, j + 1));
      const double us = 0.5 * (u_at(u, i, j - 1) + c), vs = 0.5 * (vf(i - 1, j) + vf(i, j));
      const double conv = (ue * ue - uw * uw) / hx_ + (un * vn - us * vs) / hy_;
      const double lap = lx * (u_at(u, i + 1, j) - 2.0 * c + u_at(u, i - 1, j)) +
                         ly * (u_at(u, i, j + 1) - 2.0 * c + u_at(u, i, j - 1));
      ru[j * (nx_ + 1) + i] = -conv + lap;
    }
  for (int j = 1; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {  // the interior horizontal faces
      const double c = v_at(v, i, j);
      const double vn = 0.5 * (c + v_at(v, i, j + 1)), vs = 0.5 * (v_at(v, i, j - 1) + c);
      // The cross flux v_x v_y at the corners (i + 1, j) and (i, j).
      const double ue = 0.5 * (u_at(u, i + 1, j - 1) + u_at(u, i + 1, j)), ve = 0.5 * (c + v_at(v, i + 1, j));
      const double uw = 0.5 * (u_at(u, i, j - 1) + u_at(u, i, j)), vw = 0.5 * (v_at(v, i - 1, j) + c);
      const double conv = (ue * ve - uw * vw) / hx_ + (vn * vn - vs * vs) / hy_;
      const double lap = lx * (v_at(v, i + 1, j) - 2.0 * c + v_at(v, i - 1, j)) +
                         ly * (v_at(v, i, j + 1) - 2.0 * c + v_at(v, i, j - 1));
      rv[j * nx_ + i] = -conv + lap;
    }
}

Eigen::VectorXd CavityNavierStokes2D::face_divergence(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
  Eigen::VectorXd d(nx_ * ny_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      d[j * nx_ + i] =
          (u[j * (nx_ + 1) + i + 1] - u[j * (nx_ + 1) + i]) / hx_ + (v[(j + 1) * nx_ + i] - v[j * nx_ + i]) / hy_;
  return d;
}

void CavityNavierStokes2D::project(Eigen::VectorXd& u, Eigen::VectorXd& v, double dt) {
  // D G φ = D v*: with A = −D G (φ_0 = 0), A φ = −D v*; then v ← v* − G φ (φ here absorbs Δt).
  const Eigen::VectorXd d = face_divergence(u, v);
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(nx_ * ny_);
  phi.tail(nx_ * ny_ - 1) = poisson_.solve(-d.tail(nx_ * ny_ - 1));
  for (int j = 0; j < ny_; ++j)
    for (int i = 1; i < nx_; ++i) u[j * (nx_ + 1) + i] -= (phi[j * nx_ + i] - phi[j * nx_ + i - 1]) / hx_;
  for (int j = 1; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) v[j * nx_ + i] -= (phi[j * nx_ + i] - phi[(j - 1) * nx_ + i]) / hy_;
  if (dt > 0.0) p_ = (rho_ / dt) * phi;
}

void CavityNavierStokes2D::update_nodes() {
  cx_.resize(nx_ * ny_);
  cy_.resize(nx_ * ny_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      cx_[j * nx_ + i] = 0.5 * (u_[j * (nx_ + 1) + i] + u_[j * (nx_ + 1) + i + 1]);
      cy_[j * nx_ + i] = 0.5 * (v_[j * nx_ + i] + v_[(j + 1) * nx_ + i]);
    }
}

double CavityNavierStokes2D::set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) {
  if (vx.size() != mesh_.size() || vy.size() != mesh_.size())
    throw std::invalid_argument("cavity Navier-Stokes: the velocity must have one value per node");
  // The faces from the nodes: the mean of the two cells a face separates, zero on the walls.
  u_.setZero();
  v_.setZero();
  for (int j = 0; j < ny_; ++j)
    for (int i = 1; i < nx_; ++i) u_[j * (nx_ + 1) + i] = 0.5 * (vx[j * nx_ + i - 1] + vx[j * nx_ + i]);
  for (int j = 1; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) v_[j * nx_ + i] = 0.5 * (vy[(j - 1) * nx_ + i] + vy[j * nx_ + i]);
  project(u_, v_, 0.0);
  update_nodes();
  time_ = 0.0;
  steps_ = 0;
  dt_prev_ = 0.0;
  p_.setZero();
  double removed = 0.0;
  for (int n = 0; n < mesh_.size(); ++n) removed = std::max(removed, std::hypot(vx[n] - cx_[n], vy[n] - cy_[n]));
  return removed;
}

bool CavityNavierStokes2D::step(double dt) {
  Eigen::VectorXd ru, rv;
  rate(u_, v_, ru, rv);
  Eigen::VectorXd u = ab2(u_, ru, ru_prev_, dt, dt_prev_), v = ab2(v_, rv, rv_prev_, dt, dt_prev_);
  const Eigen::VectorXd p_before = p_;
  project(u, v, dt);
  if (!u.allFinite() || !v.allFinite()) {
    p_ = p_before;
    return false;
  }
  u_ = std::move(u);
  v_ = std::move(v);
  ru_prev_ = std::move(ru);
  rv_prev_ = std::move(rv);
  dt_prev_ = dt;
  time_ += dt;
  ++steps_;
  update_nodes();
  return true;
}

double CavityNavierStokes2D::time_step() const {
  const double h = std::min(hx_, hy_);
  const double vmax = std::max({u_.cwiseAbs().maxCoeff(), v_.cwiseAbs().maxCoeff(), std::abs(lid_)});
  double dt = std::min(opt_.max_time_step, opt_.viscous_number * h * h / nu_);
  if (vmax > 0.0) dt = std::min(dt, opt_.cfl * h / vmax);
  return dt;
}

Eigen::VectorXd CavityNavierStokes2D::divergence() const { return face_divergence(u_, v_); }

Eigen::Vector2d CavityNavierStokes2D::velocity_at(double x, double y) const {
  // Local coordinates in cells from the walls' corner.
  const double sx = (x - (mesh_.x.origin - 0.5 * hx_)) / hx_, sy = (y - (mesh_.y.origin - 0.5 * hy_)) / hy_;
  if (sy > ny_) return {lid_, 0.0};
  if (sx < 0.0 || sx > nx_ || sy < 0.0) return {0.0, 0.0};
  // v_x on faces at (i, j + ½): i = floor(sx), j = floor(sy − ½) in −1..ny − 1.
  const int iu = std::min(static_cast<int>(sx), nx_ - 1),
            ju = std::clamp(static_cast<int>(std::floor(sy - 0.5)), -1, ny_ - 1);
  const double au = sx - iu, bu = sy - 0.5 - ju;
  const double vx = (1 - au) * (1 - bu) * u_at(u_, iu, ju) + au * (1 - bu) * u_at(u_, iu + 1, ju) +
                    (1 - au) * bu * u_at(u_, iu, ju + 1) + au * bu * u_at(u_, iu + 1, ju + 1);
  // v_y on faces at (i + ½, j): i = floor(sx − ½) in −1..nx − 1, j = floor(sy).
  const int iv = std::clamp(static_cast<int>(std::floor(sx - 0.5)), -1, nx_ - 1),
            jv = std::min(static_cast<int>(sy), ny_ - 1);
  const double av = sx - 0.5 - iv, bv = sy - jv;
  const double vy = (1 - av) * (1 - bv) * v_at(v_, iv, jv) + av * (1 - bv) * v_at(v_, iv + 1, jv) +
                    (1 - av) * bv * v_at(v_, iv, jv + 1) + av * bv * v_at(v_, iv + 1, jv + 1);
  return {vx, vy};
}

}  // namespace closurelab
