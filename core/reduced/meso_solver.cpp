#include "core/reduced/meso_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/averaging/averaging.hpp"
#include "core/reduced/averaged_force_map.hpp"
#include "core/base/errors.hpp"
#include "core/closure/reconstruction.hpp"
#include "core/base/snapshot_schedule.hpp"

namespace closurelab {

json MesoResult::to_json() const {
  return {{"status", status},
          {"message", message},
          {"steps", steps},
          {"time", time},
          {"dt", dt},
          {"wall_seconds", wall_seconds},
          {"last_relative_change", last_relative_change},
          {"deconvolution_matvecs", deconvolution_matvecs},
          {"deconvolution_seconds", deconvolution_seconds},
          {"quadrature_seconds", quadrature_seconds},
          {"quadrature", quadrature_cost.to_json()}};
}

namespace {

// A 1D axis as the x-axis of a tensor mesh (Reconstruction and the forward operators take 1D data there).
TensorMesh2D as_line(const UniformMesh1D& axis) { return TensorMesh2D{axis, UniformMesh1D{0.0, 1.0, 1, false, 0.0}}; }

TensorMesh2D column(const Scene& s, const UniformMesh1D& y_axis) {
  return TensorMesh2D{UniformMesh1D{0.0, s.box.lx, 1, true, s.box.lx}, y_axis};
}

}  // namespace

MesoSolver::MesoSolver(const Scene& scene, const AveragingKernel& kernel, Deconvolver& deconvolver,
                       StressQuadrature& quadrature, MesoSolverOptions options)
    : scene_(scene), kernel_(kernel), deconvolver_(deconvolver), quadrature_(quadrature), opt_(std::move(options)) {
  if (!scene.x_invariant) throw ConfigError("/scene", "the coarse solver handles x-invariant scenes only");
  const double target = opt_.spacing_over_eta * kernel.eta();
  periodic_ = !scene.has_walls;
  if (periodic_) {
    const int k = static_cast<int>(std::lround(scene.box.ly / target));
    if (k < 4) throw ConfigError("/solver/spacing_over_eta", "fewer than 4 coarse nodes across the domain");
    coarse_ = UniformMesh1D::cell_centred(0.0, scene.box.ly, k, true);
    fine_ = UniformMesh1D::cell_centred(0.0, scene.box.ly, scene.ny, true);
    data_ = coarse_;
    stress_axis_ = coarse_;
    if (opt_.scheme == "staggered") stress_axis_.origin += 0.5 * coarse_.spacing;
  } else {
    const double w = scene.wall_hi - scene.wall_lo;
    const int k = static_cast<int>(std::lround(w / target));
    if (k < 4)
      throw ConfigError("/solver/spacing_over_eta", "fewer than 4 coarse intervals across the channel (eta' too large)");
    coarse_ = UniformMesh1D{scene.wall_lo, w / k, k + 1, false, 0.0};  // nodes on both walls (5.6)
    // The deconvolution's data: the interior nodes. The wall nodes carry the imposed v̄ = 0 of (5.6), not an
    // average (the real average there is not zero: the window holds fluid), so they are not data; their
    // solution value is the particle velocity on the wall surface, zero by no slip. Used as data, the false
    // zero drives the reconstructed near-wall fluid backwards, the wall particles drag it forwards, and with
    // the wall constraint forces the loop diverges (measured for cc orders >= 1 and for cf).
    walls_are_data_ = opt_.balance == "force_density" && opt_.discretization != Discretization::coarse_coarse;
    data_ = walls_are_data_ ? coarse_ : UniformMesh1D{scene.wall_lo + w / k, w / k, k - 1, false, 0.0};
    const int j_lo = static_cast<int>(std::floor(scene.wall_lo / scene.dx - 0.5)) + 1;
    int count = 0;
    while ((j_lo + count + 0.5) * scene.dx < scene.wall_hi) ++count;
    fine_ = UniformMesh1D{(j_lo + 0.5) * scene.dx, scene.dx, count, false, 0.0};
    stress_axis_ = coarse_;
    if (opt_.scheme == "staggered") stress_axis_ = UniformMesh1D{scene.wall_lo + 0.5 * coarse_.spacing, coarse_.spacing, k, false, 0.0};
  }
  if (opt_.scheme != "paper" && opt_.scheme != "staggered")
    throw ConfigError("/solver/scheme", "unknown scheme '" + opt_.scheme + "'; known: paper, staggered");
  op_ = make_averaging_operator_1d(kernel, data_, fine_, opt_.discretization);
  if (!periodic_ && opt_.discretization != Discretization::coarse_coarse) {
    // The fluid rows' links, the two to the wall rows (at rest) included, weighted by the viscosity there
    // (harmonic mean across a phase interface), relative to the largest: the viscous-dissipation prior.
    const int rows = fine_.count;
    Eigen::VectorXd w(rows + 1);
    const auto mu = [&](int j) { return scene.viscosity_at(Vec2(0.0, fine_.node(std::clamp(j, 0, rows - 1)))); };
    for (int i = 0; i <= rows; ++i) {
      const double a = mu(i - 1), b = mu(i);
      w[i] = 2.0 * a * b / (a + b) / scene.max_viscosity();
    }
    op_.link_weights = w;
  }
  try {
    deconvolver_.setup(op_);
  } catch (const ConfigError& e) {
    throw ConfigError("/closure/deconvolver" + e.path(), e.message());  // strategies report relative paths
  }
  // The force-density balance needs no stress (its divergence is exact): the quadrature is not set up.
  if (opt_.balance != "force_density") {
    try {
      quadrature_.setup(scene, kernel, column(scene, stress_axis_), {"xy"});
    } catch (const ConfigError& e) {
      throw ConfigError("/quadrature" + e.path(), e.message());
    }
  }
  // F̄ (2.14) and ρ̄ (2.8) of the lattice at the coarse nodes.
  AveragingRequest req;
  req.external = true;
  // Per unit length in x, so the narrowest strip gives them at a cost independent of the scene's width.
  const Scene strip = scene.narrowest_strip();
  const ParticleSystem lattice = strip.make_particles();
  const MesoFields f = average_particles(lattice, strip.box, kernel, column(strip, coarse_), req, {}, strip.force_x);
  rho_bar_ = f.rho;
  accel_force_ = f.fx.cwiseQuotient(f.rho);
  v_ = Eigen::VectorXd::Zero(coarse_.count);
  held_.assign(coarse_.count, false);
  held_values_ = Eigen::VectorXd::Zero(coarse_.count);
  if (!periodic_ && !walls_are_data_) held_.front() = held_.back() = true;  // (5.6)/(5.14)
  if (opt_.balance != "stress_divergence" && opt_.balance != "force_density")
    throw ConfigError("/solver/balance", "unknown balance '" + opt_.balance + "'; known: stress_divergence, force_density");
  if (opt_.balance == "force_density") force_density_map_ = fluid_force_density_map(scene, kernel, coarse_);
  if (opt_.time_integration != "explicit" && opt_.time_integration != "backward_euler")
    throw ConfigError("/solver/time_integration", "unknown time integration '" + opt_.time_integration + "'; known: explicit, backward_euler");
  if (opt_.wall_node_value != "imposed" && opt_.wall_node_value != "reconstructed")
    throw ConfigError("/solver/wall_node_value", "unknown value '" + opt_.wall_node_value + "'; known: imposed, reconstructed");
  if (opt_.wall_constraint_forces && scene.has_walls && opt_.balance != "force_density")
    constraint_map_ = wall_constraint_force_map(scene, kernel, coarse_);
}

void MesoSolver::hold_nodes() {
  for (int k = 0; k < coarse_.count; ++k)
    if (held_[k]) v_[k] = held_values_[k];
}


Eigen::VectorXd MesoSolver::constraint_force() {
  return constraint_map_.apply(sample_reconstruction(constraint_map_.rows).row(0).transpose());
}

Eigen::VectorXd MesoSolver::wall_constraint_force() {
  if (constraint_map_.rows.empty()) return Eigen::VectorXd::Zero(coarse_.count);
  std::string issue;
  if (!close_stress(issue)) throw NumericalError(issue);
  return constraint_force();
}

void MesoSolver::set_velocity(const Eigen::VectorXd& v) {
  if (v.size() != v_.size()) throw ConfigError("", "velocity has the wrong size");
  v_ = v;
  hold_nodes();
}

Eigen::Matrix2Xd MesoSolver::sample_reconstruction(const std::vector<Vec2>& points) {
  const bool fine_solution = opt_.discretization != Discretization::coarse_coarse;
  const Reconstruction rec(as_line(fine_solution ? fine_ : coarse_), 1, reconstruction_);
  Eigen::Matrix2Xd out = Eigen::Matrix2Xd::Zero(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!scene_.is_wall(points[i].y())) {
      double v = rec.sample(Vec2(points[i].y(), 0.0));
      if (oracle_correction_) v += oracle_correction_->sample(Vec2(points[i].y(), 0.0));
      out(0, static_cast<Eigen::Index>(i)) = v;
    }
  return out;
}

bool MesoSolver::deconvolve(std::string& issue) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const bool walls_off = !periodic_ && opt_.discretization != Discretization::fine_fine && !walls_are_data_;
  Eigen::VectorXd b = walls_off ? Eigen::VectorXd(v_.segment(1, v_.size() - 2)) : v_;
  if (opt_.discretization == Discretization::fine_fine) {
    std::vector<Vec2> pts;
    for (int j = 0; j < fine_.count; ++j) pts.emplace_back(fine_.node(j), 0.0);
    b = Reconstruction(as_line(coarse_), 1, v_).sample(pts);  // linear interpolation of the coarse data
  }
  const DeconvolutionResult r = deconvolver_.solve(b, opt_.noise_level);
  matvecs_ += r.cost.matvecs;
  if (walls_off && opt_.discretization == Discretization::coarse_coarse) {
    reconstruction_ = Eigen::VectorXd::Zero(v_.size());  // zero on the wall surfaces (no slip)
    reconstruction_.segment(1, v_.size() - 2) = r.x;
  } else {
    reconstruction_ = r.x;
  }
  deconv_seconds_ += std::chrono::duration<double>(clock::now() - t0).count();
  if (!reconstruction_.allFinite()) {
    issue = "deconvolution returned non-finite values (" + r.stats.message + ")";
    return false;
  }
  return true;
}

bool MesoSolver::close_stress(std::string& issue) {
  if (!deconvolve(issue)) return false;
  const auto t1 = std::chrono::steady_clock::now();
  auto out = quadrature_.evaluate([this](const std::vector<Vec2>& p) { return sample_reconstruction(p); });
  t_ = out.at("xy");
  quad_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  if (!t_.allFinite()) {
    issue = "interaction stress is not finite";
    return false;
  }
  return true;
}

bool MesoSolver::rate(Eigen::VectorXd& dvdt, std::string& issue) {
  const int n = coarse_.count;
  if (opt_.balance == "force_density") {
    if (!deconvolve(issue)) return false;
    const auto t1 = std::chrono::steady_clock::now();
    const Eigen::VectorXd density = force_density_map_.apply(sample_reconstruction(force_density_map_.rows).row(0).transpose());
    quad_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    if (!density.allFinite()) {
      issue = "force density is not finite";
      return false;
    }
    dvdt = density.cwiseQuotient(rho_bar_) + accel_force_;
    return true;
  }
  if (!close_stress(issue)) return false;
  const double h = coarse_.spacing;
  Eigen::VectorXd dtdy = Eigen::VectorXd::Zero(n);
  const auto wrap = [n](int k) { return (k % n + n) % n; };
  if (periodic_) {
    for (int k = 0; k < n; ++k)
      dtdy[k] = opt_.scheme == "paper" ? (t_[wrap(k + 1)] - t_[wrap(k - 1)]) / (2 * h) : (t_[k] - t_[wrap(k - 1)]) / h;
  } else {
    const int kk = n - 1;  // wall nodes 0 and kk
    for (int k = 1; k < kk; ++k) {
      if (opt_.scheme == "staggered") {
        dtdy[k] = (t_[k] - t_[k - 1]) / h;  // T at mid-nodes k − 1/2 and k + 1/2
      } else if (k == 1) {
        dtdy[k] = (t_[2] - t_[1]) / h;  // (5.11)
      } else if (k == kk - 1) {
        dtdy[k] = (t_[kk - 1] - t_[kk - 2]) / h;  // (5.13)
      } else {
        dtdy[k] = (t_[k + 1] - t_[k - 1]) / (2 * h);  // (5.12)
      }
    }
  }
  if (!constraint_map_.rows.empty()) dtdy += constraint_force();
  dvdt = dtdy.cwiseQuotient(rho_bar_) + accel_force_;
  return true;
}

double MesoSolver::time_step() const {
  const double h = coarse_.spacing, vmax = v_.cwiseAbs().maxCoeff();
  double dt = scene_.rho0 * h * h / scene_.max_viscosity();  // (5.22)
  if (vmax > 0) dt = std::min(dt, h / vmax);                 // (5.21)
  return opt_.kappa * dt;
}

MesoResult MesoSolver::run() {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto last_report = t0;
  MesoResult res;
  res.status = "no_convergence";
  Eigen::VectorXd reference = v_;
  SnapshotSchedule snapshots(opt_.snapshot_times);
  while (res.steps < opt_.max_steps) {
    const double dt_full = time_step();  // reported; snapshots and the target time may shorten a step
    double dt = snapshots.clamp(res.time, dt_full);
    if (!opt_.to_steady_state) {
      if (res.time >= opt_.target_time * (1.0 - 1e-14)) {
        res.status = "target_time";
        break;
      }
      dt = std::min(dt, opt_.target_time - res.time);
    } else if (res.time >= opt_.max_time) {
      break;
    }
    std::string issue;
    if (!step(dt, issue)) {
      res.status = "numerical_issue";
      res.message = issue;
      break;
    }
    res.dt = dt_full;
    res.time += dt;
    ++res.steps;
    if (snapshots.due(res.time) && opt_.on_snapshot) opt_.on_snapshot(res.time, reported_velocity());
    if (res.steps % opt_.steady_window == 0) {
      const double mag = v_.cwiseAbs().maxCoeff();
      res.last_relative_change = mag > 0 ? (v_ - reference).cwiseAbs().maxCoeff() / mag : 0.0;
      reference = v_;
      if (!v_.allFinite()) {
        res.status = "numerical_issue";
        res.message = "coarse velocity is not finite";
        break;
      }
      if (scene_.analytic_peak > 0 && mag > opt_.divergence_factor * scene_.analytic_peak) {
        std::ostringstream os;
        os << "diverged: max|v| = " << mag << " exceeds " << opt_.divergence_factor << " x the analytic peak";
        res.status = "numerical_issue";
        res.message = os.str();
        break;
      }
      if (opt_.to_steady_state && res.steps > opt_.steady_window && res.last_relative_change < opt_.steady_tolerance) {
        res.status = "converged";
        break;
      }
      const auto now = clock::now();
      if (opt_.progress && std::chrono::duration<double>(now - last_report).count() >= opt_.progress_seconds) {
        last_report = now;
        std::ostringstream os;
        os << "reduced model: step " << res.steps << ", t = " << res.time << ", max|v| = " << mag
           << ", change over " << opt_.steady_window << " steps = " << res.last_relative_change;
        opt_.progress(os.str());
      }
    }
  }
  if (res.status != "numerical_issue" && !v_.allFinite()) {
    res.status = "numerical_issue";
    res.message = "coarse velocity is not finite";
  }
  res.wall_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  res.y = coarse_.nodes();
  res.v = reported_velocity();
  res.deconvolution_matvecs = matvecs_;
  res.deconvolution_seconds = deconv_seconds_;
  res.quadrature_seconds = quad_seconds_;
  res.quadrature_cost = quadrature_.cost();
  return res;
}

}  // namespace closurelab
