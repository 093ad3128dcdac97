#include "core/meso_solver.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "core/averaging.hpp"
#include "core/errors.hpp"
#include "core/reconstruction.hpp"

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
    stress_axis_ = coarse_;
    if (opt_.scheme == "staggered") stress_axis_.origin += 0.5 * coarse_.spacing;
  } else {
    const double w = scene.wall_hi - scene.wall_lo;
    const int k = static_cast<int>(std::lround(w / target));
    if (k < 4)
      throw ConfigError("/solver/spacing_over_eta", "fewer than 4 coarse intervals across the channel (eta' too large)");
    coarse_ = UniformMesh1D{scene.wall_lo, w / k, k + 1, false, 0.0};  // nodes on both walls (5.6)
    const int j_lo = static_cast<int>(std::floor(scene.wall_lo / scene.dx - 0.5)) + 1;
    int count = 0;
    while ((j_lo + count + 0.5) * scene.dx < scene.wall_hi) ++count;
    fine_ = UniformMesh1D{(j_lo + 0.5) * scene.dx, scene.dx, count, false, 0.0};
    stress_axis_ = coarse_;
    if (opt_.scheme == "staggered") stress_axis_ = UniformMesh1D{scene.wall_lo + 0.5 * coarse_.spacing, coarse_.spacing, k, false, 0.0};
  }
  if (opt_.scheme != "paper" && opt_.scheme != "staggered")
    throw ConfigError("/solver/scheme", "unknown scheme '" + opt_.scheme + "'; known: paper, staggered");
  op_ = make_averaging_operator_1d(kernel, coarse_, fine_, opt_.discretization);
  try {
    deconvolver_.setup(op_);
  } catch (const ConfigError& e) {
    throw ConfigError("/closure/deconvolver" + e.path(), e.message());  // strategies report relative paths
  }
  try {
    quadrature_.setup(scene, kernel, column(scene, stress_axis_), {"xy"});
  } catch (const ConfigError& e) {
    throw ConfigError("/quadrature" + e.path(), e.message());
  }
  // F̄ (2.14) and ρ̄ (2.8) of the lattice at the coarse nodes.
  AveragingRequest req;
  req.external = true;
  const ParticleSystem lattice = scene.make_particles();
  const MesoFields f = average_particles(lattice, scene.box, kernel, column(scene, coarse_), req, {}, scene.force_x);
  rho_bar_ = f.rho;
  accel_force_ = f.fx.cwiseQuotient(f.rho);
  v_ = Eigen::VectorXd::Zero(coarse_.count);
  if (opt_.wall_constraint_forces && scene.has_walls) {
    lattice_ = lattice;
    engine_ = std::make_unique<SphEngine>(scene, lattice_);
    const double reach = 2.0 * scene.h * 3.0;  // wall particles that interact with fluid particles
    for (std::size_t a = 0; a < lattice_.size(); ++a)
      if (lattice_.fixed[a] && (lattice_.y[a] > scene.wall_lo - reach && lattice_.y[a] < scene.wall_hi + reach))
        wall_ids_.push_back(static_cast<std::int32_t>(a));
    wall_weights_ = Eigen::MatrixXd::Zero(coarse_.count, static_cast<Eigen::Index>(wall_ids_.size()));
    const double r = kernel.support_radius();
    for (std::size_t w = 0; w < wall_ids_.size(); ++w) {
      const int a = wall_ids_[w];
      double wx = 0.0;  // the column sits at x = 0; sum the periodic images in x
      for (int k = static_cast<int>(std::floor((-r - lattice_.x[a]) / scene.box.lx));
           k <= static_cast<int>(std::ceil((r - lattice_.x[a]) / scene.box.lx)); ++k)
        wx += kernel.factor(lattice_.x[a] + k * scene.box.lx);
      for (int n = 0; n < coarse_.count; ++n)
        wall_weights_(n, static_cast<Eigen::Index>(w)) = wx * kernel.factor(coarse_.node(n) - lattice_.y[a]);
    }
  }
}

Eigen::VectorXd MesoSolver::constraint_force() {
  std::vector<Vec2> pts;
  std::vector<std::int32_t> fluid;
  for (std::size_t a = 0; a < lattice_.size(); ++a)
    if (!lattice_.fixed[a]) fluid.push_back(static_cast<std::int32_t>(a)), pts.emplace_back(lattice_.x[a], lattice_.y[a]);
  const Eigen::Matrix2Xd v = sample_reconstruction(pts);
  for (std::size_t k = 0; k < fluid.size(); ++k) {
    lattice_.vx[fluid[k]] = v(0, static_cast<Eigen::Index>(k));
    lattice_.vy[fluid[k]] = v(1, static_cast<Eigen::Index>(k));
  }
  std::vector<double> net(lattice_.size(), 0.0);  // x-force on each particle
  for (const PairForce& p : engine_->pair_forces()) {
    net[p.j] += p.f.x();
    net[p.k] -= p.f.x();
  }
  Eigen::VectorXd c(static_cast<Eigen::Index>(wall_ids_.size()));
  for (std::size_t w = 0; w < wall_ids_.size(); ++w) c[static_cast<Eigen::Index>(w)] = -net[wall_ids_[w]];
  return wall_weights_ * c;
}

void MesoSolver::set_velocity(const Eigen::VectorXd& v) {
  if (v.size() != v_.size()) throw ConfigError("", "velocity has the wrong size");
  v_ = v;
  if (!periodic_) v_[0] = v_[v_.size() - 1] = 0.0;
}

Eigen::Matrix2Xd MesoSolver::sample_reconstruction(const std::vector<Vec2>& points) {
  const bool fine_solution = opt_.discretization != Discretization::coarse_coarse;
  const Reconstruction rec(as_line(fine_solution ? fine_ : coarse_), 1, reconstruction_);
  Eigen::Matrix2Xd out = Eigen::Matrix2Xd::Zero(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!scene_.is_wall(points[i].y())) out(0, static_cast<Eigen::Index>(i)) = rec.sample(Vec2(points[i].y(), 0.0));
  return out;
}

bool MesoSolver::close_stress(std::string& issue) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  Eigen::VectorXd b = v_;
  if (opt_.discretization == Discretization::fine_fine) {
    std::vector<Vec2> pts;
    for (int j = 0; j < fine_.count; ++j) pts.emplace_back(fine_.node(j), 0.0);
    b = Reconstruction(as_line(coarse_), 1, v_).sample(pts);  // linear interpolation of the coarse data
  }
  const DeconvolutionResult r = deconvolver_.solve(b, opt_.noise_level);
  matvecs_ += r.cost.matvecs;
  reconstruction_ = r.x;
  const auto t1 = clock::now();
  deconv_seconds_ += std::chrono::duration<double>(t1 - t0).count();
  if (!reconstruction_.allFinite()) {
    issue = "deconvolution returned non-finite values (" + r.stats.message + ")";
    return false;
  }
  auto out = quadrature_.evaluate([this](const std::vector<Vec2>& p) { return sample_reconstruction(p); });
  t_ = out.at("xy");
  quad_seconds_ += std::chrono::duration<double>(clock::now() - t1).count();
  if (!t_.allFinite()) {
    issue = "interaction stress is not finite";
    return false;
  }
  return true;
}

bool MesoSolver::step(double dt, std::string& issue) {
  if (!close_stress(issue)) return false;
  const int n = coarse_.count;
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
  if (engine_) dtdy += constraint_force();
  for (int k = 0; k < n; ++k) v_[k] += dt * (dtdy[k] / rho_bar_[k] + accel_force_[k]);
  if (!periodic_) v_[0] = v_[n - 1] = 0.0;  // (5.14)
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
  while (res.steps < opt_.max_steps) {
    double dt = time_step();
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
    res.dt = dt;
    res.time += dt;
    ++res.steps;
    if (res.steps % opt_.steady_window == 0) {
      const double mag = v_.cwiseAbs().maxCoeff();
      res.last_relative_change = mag > 0 ? (v_ - reference).cwiseAbs().maxCoeff() / mag : 0.0;
      reference = v_;
      if (!v_.allFinite()) {
        res.status = "numerical_issue";
        res.message = "coarse velocity is not finite";
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
  res.v = v_;
  res.deconvolution_matvecs = matvecs_;
  res.deconvolution_seconds = deconv_seconds_;
  res.quadrature_seconds = quad_seconds_;
  res.quadrature_cost = quadrature_.cost();
  return res;
}

}  // namespace closurelab
