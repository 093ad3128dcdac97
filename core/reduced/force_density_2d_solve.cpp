// The 2D force-density model, its solve: the closure applied (the two deconvolutions), the rates, the steady state by
// the probed and bordered linear system, and what a run reports (core/reduced/force_density_2d.hpp); the maps are
// assembled in force_density_2d.cpp.
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/base/repeated_timing.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "core/reduced/force_density_2d_assembly.hpp"

namespace closurelab {

void ForceDensitySolver2D::set_state(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy, const Eigen::VectorXd& n) {
  const Eigen::Index nc = coarse_.size();
  if (vx.size() != nc || vy.size() != nc || n.size() != nc) throw ConfigError("", "state has the wrong size");
  for (std::size_t k = 0; k < free_.size(); ++k) {
    vx_[static_cast<Eigen::Index>(k)] = vx[free_[k]];
    vy_[static_cast<Eigen::Index>(k)] = vy[free_[k]];
    n_[static_cast<Eigen::Index>(k)] = n[free_[k]];
  }
}

Eigen::VectorXd ForceDensitySolver2D::interpolate_to_particles(const Eigen::VectorXd& x) const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(interp_.size()));
  for (std::size_t a = 0; a < interp_.size(); ++a) {
    double v = 0.0;
    for (int k = 0; k < 4; ++k) v += interp_[a].weight[k] * x[interp_[a].node[k]];
    out[static_cast<Eigen::Index>(a)] = v;
  }
  return out;
}

bool ForceDensitySolver2D::deconvolve(Deconvolver& d, const Eigen::VectorXd& data, Eigen::VectorXd& x,
                                      std::string& issue) {
  Eigen::MatrixXd one;
  if (!deconvolve_columns(d, Eigen::MatrixXd(data), one, issue)) return false;
  x = one.col(0);
  return true;
}

bool ForceDensitySolver2D::deconvolve_columns(Deconvolver& d, const Eigen::MatrixXd& data, Eigen::MatrixXd& x,
                                              std::string& issue) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<DeconvolutionResult> results;
  Eigen::MatrixXd r = d.solve_columns(data, opt_.noise_level, &results);
  for (const DeconvolutionResult& one : results) {
    matvecs_ += one.cost.matvecs;
    deconvolution_issues_.count(one);
  }
  deconv_seconds_ += seconds_since(t0);
  if (&d == &velocity_) {  // on every reconstruction node: zero inside the solid
    x = Eigen::MatrixXd::Zero(recon_.size(), data.cols());
    for (std::size_t k = 0; k < velocity_columns_.size(); ++k) x.row(velocity_columns_[k]) = r.row(static_cast<Eigen::Index>(k));
  } else {
    x = std::move(r);
  }
  if (!x.allFinite()) {
    issue = "deconvolution returned non-finite values" +
            (results.empty() || results.front().stats.message.empty() ? "" : " (" + results.front().stats.message + ")");
    return false;
  }
  return true;
}

Eigen::VectorXd ForceDensitySolver2D::on_free(const Eigen::VectorXd& full) const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(free_.size()));
  for (std::size_t k = 0; k < free_.size(); ++k) out[static_cast<Eigen::Index>(k)] = full[free_[k]];
  return out;
}

bool ForceDensitySolver2D::rate(Eigen::VectorXd& ax, Eigen::VectorXd& ay, Eigen::VectorXd& an, std::string& issue) {
  Eigen::VectorXd rx, ry, rn;
  if (!deconvolve(velocity_, vx_, rx, issue) || !deconvolve(velocity_, vy_, ry, issue) ||
      !deconvolve(density_, n_, rn, issue))
    return false;
  Eigen::VectorXd fx, fy, fn;
  rates_from_reconstruction(rx, ry, rn, fx, fy, fn);
  ax = on_free(fx);
  ay = on_free(fy);
  an = on_free(fn);
  return true;
}

void ForceDensitySolver2D::rates_from_reconstruction(const Eigen::VectorXd& rx, const Eigen::VectorXd& ry,
                                                     const Eigen::VectorXd& rn, Eigen::VectorXd& ax,
                                                     Eigen::VectorXd& ay, Eigen::VectorXd& an) const {
  ax = viscous_ * rx + pressure_x_ * rn + body_x_;
  ay = viscous_ * ry + pressure_y_ * rn + body_y_;
  an = continuity_x_ * rx + continuity_y_ * ry;
  if (opt_.convective_stress) {
    Eigen::VectorXd qx, qy;
    convective_rates(rx, ry, qx, qy);
    ax += qx;
    ay += qy;
  }
}

namespace force_density_detail {

// big z = rhs by LU, equilibrated (rows, then columns, to unit largest entry): the momentum and density rows differ in
// units, and free nodes with a small fluid fraction have small rows; the condition estimate is then of the problem
// itself. False (the reason in `issue`) when the system is singular to working precision. With `minimum_norm`, a
// rank-deficient system is solved by a complete orthogonal decomposition (the minimum-norm solution of the equilibrated
// system), which must then satisfy it to 1e-9 of the right-hand side.
bool equilibrated_steady_solve(Eigen::MatrixXd big, const Eigen::VectorXd& rhs, Eigen::VectorXd& z, std::string& issue,
                               bool minimum_norm) {
  const Eigen::VectorXd row_scale = big.rowwise().lpNorm<Eigen::Infinity>().cwiseMax(1e-300).cwiseInverse();
  big = row_scale.asDiagonal() * big;
  const Eigen::VectorXd col_scale = big.colwise().lpNorm<Eigen::Infinity>().transpose().cwiseMax(1e-300).cwiseInverse();
  big = big * col_scale.asDiagonal();
  const Eigen::VectorXd b = row_scale.cwiseProduct(rhs);
  std::ostringstream os;
  if (minimum_norm) {
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(big);
    const Eigen::VectorXd zs = cod.solve(b);
    const double residual = (big * zs - b).norm() / std::max(b.norm(), 1e-300);
    z = col_scale.cwiseProduct(zs);
    if (z.allFinite() && residual < 1e-9) return true;
    os << "the steady system has no solution to working precision (relative residual " << residual << ", rank "
       << cod.rank() << " of " << big.rows() << ")";
    issue = os.str();
    return false;
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(big);
  z = col_scale.cwiseProduct(lu.solve(b));
  if (!z.allFinite() || lu.rcond() < 1e-15) {
    os << "the steady system is singular to working precision (reciprocal condition " << lu.rcond() << ")";
    issue = os.str();
    return false;
  }
  return true;
}

}  // namespace force_density_detail

using force_density_detail::equilibrated_steady_solve;

bool ForceDensitySolver2D::steady_solve(std::string& issue) {
  // The rate is affine in the state z = (v̄_x, v̄_y, n̄) on the free nodes: rate = M z + c. Probed on unit data
  // (the closure is linear: check_force_density_closure), then M z = −c solved with the total density deviation
  // Σ n̄ ρ̄-weights = 0 bordering it: the rate does not see a uniform n̄ (a uniform pressure exerts no force on
  // the lattice), so M has that null direction. In an x-invariant scene v̄_y and n̄ stay zero (ṅ cancels pair by pair
  // along each lattice row, so nothing drives them) and the x-momentum alone is solved: the pressure's
  // linearisation, which a van der Waals scene does not have, is not used.
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index f = static_cast<Eigen::Index>(free_.size());
  const Eigen::MatrixXd unit = Eigen::MatrixXd::Identity(f, f);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(f);
  Eigen::MatrixXd xv, xn;
  Eigen::VectorXd x0v, x0n;  // the closure's response to zero data (affine part)
  if (!deconvolve_columns(velocity_, unit, xv, issue) || !deconvolve(velocity_, zero, x0v, issue)) return false;
  // The blocks of M on every node (a product of the full map, no copy of it), then the free rows.
  const auto free_rows_of = [&](const Eigen::MatrixXd& full) {
    Eigen::MatrixXd out(f, full.cols());
    for (Eigen::Index k = 0; k < f; ++k) out.row(k) = full.row(free_[static_cast<std::size_t>(k)]);
    return out;
  };
  const Eigen::MatrixXd mvv = free_rows_of(viscous_ * xv);
  Eigen::VectorXd z;
  if (scene_.x_invariant) {
    probe_seconds_ = seconds_since(t0);
    if (!equilibrated_steady_solve(mvv, -on_free(viscous_ * x0v + body_x_), z, issue, false)) return false;
    vx_ = z;
    vy_ = n_ = zero;
    return true;
  }
  if (!deconvolve_columns(density_, unit, xn, issue) || !deconvolve(density_, zero, x0n, issue)) return false;
  const Eigen::MatrixXd mxn = free_rows_of(pressure_x_ * xn), myn = free_rows_of(pressure_y_ * xn),
                        mnx = free_rows_of(continuity_x_ * xv), mny = free_rows_of(continuity_y_ * xv);
  // Without a solid (the cellular flow) a uniform velocity exerts no force either (Galilean invariance): the cell's
  // momentum in x and in y borders the system too, zero as from rest (a periodic force of zero mean keeps it there).
  // And the coarse mesh's odd density modes ((−1)^i, (−1)^j, (−1)^(i+j)) are even about every node, so their averaged
  // pressure force vanishes there by symmetry (the collocated-grid pressure modes; a solid breaks the symmetry): the
  // system stays singular in n̄ along them, which moves no velocity, and its minimum-norm solution is taken.
  const bool has_solid = std::find(fixed_.begin(), fixed_.end(), std::uint8_t{1}) != fixed_.end();
  const Eigen::Index borders = has_solid ? 1 : 3, size = 3 * f + borders;
  Eigen::MatrixXd big = Eigen::MatrixXd::Zero(size, size);
  big.block(0, 0, f, f) = mvv;
  big.block(0, 2 * f, f, f) = mxn;
  big.block(f, f, f, f) = mvv;
  big.block(f, 2 * f, f, f) = myn;
  big.block(2 * f, 0, f, f) = mnx;
  big.block(2 * f, f, f, f) = mny;
  const Eigen::VectorXd weight = on_free(mass_weight_);
  for (Eigen::Index k = 0; k < borders; ++k) {  // k = 0: the density deviation; 1, 2: the momentum in x, y
    const Eigen::Index block = k == 0 ? 2 * f : (k - 1) * f;
    big.block(block, 3 * f + k, f, 1).setConstant(1.0);  // the multiplier of the free direction
    big.block(3 * f + k, block, 1, f) = weight.transpose();
  }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
  rhs.segment(0, f) = -on_free(viscous_ * x0v + pressure_x_ * x0n + body_x_);
  rhs.segment(f, f) = -on_free(viscous_ * x0v + pressure_y_ * x0n + body_y_);
  rhs.segment(2 * f, f) = -on_free(continuity_x_ * x0v + continuity_y_ * x0v);
  probe_seconds_ = seconds_since(t0);
  // With the convective flux: the Stokes solution, then Newton's iteration from it.
  const Eigen::MatrixXd stokes = opt_.convective_stress ? big : Eigen::MatrixXd();
  if (!equilibrated_steady_solve(std::move(big), rhs, z, issue, !has_solid)) return false;
  if (opt_.convective_stress && !newton_convective(stokes, rhs, xv, x0v, !has_solid, z, issue)) return false;
  vx_ = z.segment(0, f);
  vy_ = z.segment(f, f);
  n_ = z.segment(2 * f, f);
  return true;
}

double ForceDensitySolver2D::superficial_velocity(std::string& issue) {
  Eigen::VectorXd rx;
  if (!deconvolve(velocity_, vx_, rx, issue)) return std::nan("");
  const Eigen::VectorXd v = interpolate_to_particles(rx);
  double sum = 0.0;
  for (Eigen::Index a = 0; a < v.size(); ++a)
    if (!fixed_[static_cast<std::size_t>(a)]) sum += v[a];
  return sum * fluid_area_per_particle_;
}

Eigen::VectorXd ForceDensitySolver2D::reported(const Eigen::VectorXd& state, Deconvolver& d,
                                               const RowMajorMatrix& full, std::string& issue) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(coarse_.size()), x;
  if (opt_.held_node_value == HeldNodeValue::reconstructed && free_.size() < static_cast<std::size_t>(coarse_.size())) {
    if (!deconvolve(d, state, x, issue)) return Eigen::VectorXd::Constant(coarse_.size(), std::nan(""));
    out = full * x;  // held nodes: the average of the reconstruction
  }
  for (std::size_t k = 0; k < free_.size(); ++k) out[free_[k]] = state[static_cast<Eigen::Index>(k)];
  return out;
}

ForceDensity2DResult ForceDensitySolver2D::run() {
  ForceDensity2DResult res;
  std::string issue;
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  if (stepper_) {
    march(res);  // the loop's status, message and times
    issue = res.message;
  } else {
    const bool ok = steady_solve(issue);
    res.status = ok ? Status::converged : Status::numerical_issue;
    res.message = issue;
    res.wall_seconds = seconds_since(t0);
    res.cpu_seconds = process_cpu_seconds() - cpu0;
  }
  res.mesh = coarse_;
  res.vx = reported(vx_, velocity_, full_v_, issue);
  res.vy = reported(vy_, velocity_, full_v_, issue);
  res.density = reported(n_, density_, full_n_, issue);
  res.superficial_velocity = superficial_velocity(issue);
  if ((res.status == Status::converged || res.status == Status::target_time) &&
      (!res.vx.allFinite() || !res.vy.allFinite())) {
    res.status = Status::numerical_issue;
    res.message = issue;
  }
  res.free_nodes = static_cast<long>(free_.size());
  res.reconstruction_nodes = recon_.size();
  res.deconvolution_matvecs = matvecs_;
  res.deconvolution_issues = deconvolution_issues_;
  res.deconvolution_seconds = deconv_seconds_;
  res.setup_seconds = setup_seconds_;
  res.assembly_seconds = assembly_seconds_;
  res.probe_seconds = probe_seconds_;
  res.newton_iterations = newton_iterations_;
  res.newton_seconds = newton_seconds_;
  res.newton_last_step = newton_last_step_;
  res.rate_evaluations = rate_evaluations_;
  return res;
}

}  // namespace closurelab
