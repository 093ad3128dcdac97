#include "core/reduced/meso_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/averaging/averaging.hpp"
#include "core/reduced/averaged_force_map.hpp"
#include "core/reduced/reduced_grid.hpp"
#include "core/base/errors.hpp"
#include "core/closure/reconstruction.hpp"

namespace closurelab {

void ParameterChoiceRecord::add(const DeconvolutionStats& stats) {
  if (stats.rule.empty() || stats.rule == "fixed") return;
  const double p = stats.chosen_parameter;
  if (solves++ == 0) {
    rule = stats.rule;
    parameter_name = stats.parameter_name;
    first = min = max = p;
  }
  last = p;
  min = std::min(min, p);
  max = std::max(max, p);
  if (!stats.note.empty() && noted_solves++ == 0) first_note = stats.note;
}

json ParameterChoiceRecord::to_json() const {
  json j = {{"rule", rule}, {"parameter", parameter_name}, {"solves", solves},
            {"first", first}, {"last", last}, {"min", min}, {"max", max}};
  if (noted_solves > 0) j["notes"] = {{"solves", noted_solves}, {"first", first_note}};
  return j;
}

void DeconvolutionIssues::count(const DeconvolutionResult& r) {
  if (r.status != Status::numerical_issue) return;
  if (solves++ == 0) first = r.stats.message;
}

json ClosureRunResult::to_json() const {
  json j = TimeLoopResult::to_json();
  if (deconvolution_issues.solves > 0)
    j["deconvolution_issues"] = {{"solves", deconvolution_issues.solves}, {"first", deconvolution_issues.first}};
  if (parameter_choice.solves > 0) j["parameter_choice"] = parameter_choice.to_json();
  j["message"] = message;
  j["deconvolution_matvecs"] = deconvolution_matvecs;
  j["deconvolution_seconds"] = deconvolution_seconds;
  j["quadrature_seconds"] = quadrature_seconds;
  j["quadrature"] = quadrature_cost.to_json();
  return j;
}

namespace {

// A 1D axis as the x-axis of a tensor mesh (Reconstruction and the forward operators take 1D data there).
TensorMesh2D as_line(const UniformMesh1D& axis) { return TensorMesh2D{axis, UniformMesh1D{0.0, 1.0, 1, false, 0.0}}; }


}  // namespace

ReducedGrid reduced_grid(const Scene& scene, const AveragingKernel& kernel, const MesoSolverOptions& o) {
  // The wall-surface nodes are evolved, and are deconvolution data, under the force-density balance when the
  // solution lives on the fine rows (coarse–fine, fine–fine).
  return make_reduced_grid(scene, kernel, o.spacing_over_eta, o.scheme == MesoScheme::staggered,
                           o.balance == MesoBalance::force_density && o.discretization != Discretization::coarse_coarse);
}

void check_meso_solver(const Scene& scene, const AveragingKernel& kernel, const StressQuadrature& quadrature,
                       const MesoSolverOptions& o) {
  const ReducedGrid grid = reduced_grid(scene, kernel, o);
  if (o.balance != MesoBalance::force_density) {
    try {
      quadrature.check(scene, column_of(scene, grid.stress_axis), {"xy"});
    } catch (const ConfigError& e) {
      throw ConfigError("/quadrature" + e.path(), e.message());
    }
  }
}

MesoSolver::MesoSolver(const Scene& scene, const AveragingKernel& kernel, Deconvolver& deconvolver,
                       StressQuadrature& quadrature, Integrator& integrator, MesoSolverOptions options)
    : scene_(scene),
      kernel_(kernel),
      deconvolver_(deconvolver),
      quadrature_(quadrature),
      integrator_(integrator),
      opt_(std::move(options)) {
  const ReducedGrid grid = reduced_grid(scene, kernel, opt_);
  coarse_ = grid.coarse;
  data_ = grid.data;
  fine_ = grid.fine;
  stress_axis_ = grid.stress_axis;
  periodic_ = grid.periodic;
  walls_are_data_ = grid.walls_are_data;
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
  if (opt_.balance != MesoBalance::force_density) {
    try {
      quadrature_.setup(scene, kernel, column_of(scene, stress_axis_), {"xy"});
      quad_cost_ = quadrature_.setup_cost();
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
  const MesoFields f = average_particles(lattice, strip.box, kernel, column_of(strip, coarse_), req, {}, strip.force_x);
  rho_bar_ = f.rho;
  accel_force_ = f.fx.cwiseQuotient(f.rho);
  v_ = Eigen::VectorXd::Zero(coarse_.count);
  held_.assign(coarse_.count, false);
  held_values_ = Eigen::VectorXd::Zero(coarse_.count);
  if (!periodic_ && !walls_are_data_) held_.front() = held_.back() = true;  // (5.6)/(5.14)
  if (opt_.balance == MesoBalance::force_density) force_density_map_ = fluid_force_density_map(scene, kernel, coarse_);
  if (opt_.wall_constraint_forces && scene.has_walls && opt_.balance != MesoBalance::force_density)
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

Eigen::VectorXd MesoSolver::deconvolution_data() const {
  const bool walls_off = !periodic_ && opt_.discretization != Discretization::fine_fine && !walls_are_data_;
  if (opt_.discretization == Discretization::fine_fine) {
    std::vector<Vec2> pts;
    for (int j = 0; j < fine_.count; ++j) pts.emplace_back(fine_.node(j), 0.0);
    return Reconstruction(as_line(coarse_), 1, v_).sample(pts);  // linear interpolation of the coarse data
  }
  return walls_off ? Eigen::VectorXd(v_.segment(1, v_.size() - 2)) : v_;
}

bool MesoSolver::deconvolve(std::string& issue) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const bool walls_off = !periodic_ && opt_.discretization != Discretization::fine_fine && !walls_are_data_;
  const DeconvolutionResult r = deconvolver_.solve(deconvolution_data(), opt_.noise_level);
  matvecs_ += r.cost.matvecs;
  choice_.add(r.stats);
  deconvolution_issues_.count(r);
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
  const QuadratureResult r = quadrature_.evaluate([this](const std::vector<Vec2>& p) { return sample_reconstruction(p); });
  quad_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  quad_cost_.add(r);
  if (r.status != Status::converged) {
    issue = r.message;
    return false;
  }
  t_ = r.stress.at("xy");
  return true;
}

bool MesoSolver::rate(Eigen::VectorXd& dvdt, std::string& issue) {
  const int n = coarse_.count;
  if (opt_.balance == MesoBalance::force_density) {
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
      dtdy[k] = opt_.scheme == MesoScheme::paper ? (t_[wrap(k + 1)] - t_[wrap(k - 1)]) / (2 * h) : (t_[k] - t_[wrap(k - 1)]) / h;
  } else {
    const int kk = n - 1;  // wall nodes 0 and kk
    for (int k = 1; k < kk; ++k) {
      if (opt_.scheme == MesoScheme::staggered) {
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

double coarse_time_step(double kappa, double rho, double spacing, double max_viscosity, double max_speed) {
  double dt = rho * spacing * spacing / max_viscosity;        // (5.22)
  if (max_speed > 0) dt = std::min(dt, spacing / max_speed);  // (5.21)
  return kappa * dt;
}

bool coarse_state_ok(bool finite, double max_abs, double analytic_peak, double divergence_factor, std::string& issue) {
  if (!finite) {
    issue = "coarse velocity is not finite";
    return false;
  }
  if (analytic_peak > 0 && max_abs > divergence_factor * analytic_peak) {
    std::ostringstream os;
    os << "diverged: max|v| = " << max_abs << " exceeds " << divergence_factor << " x the analytic peak";
    issue = os.str();
    return false;
  }
  return true;
}

double MesoSolver::time_step() const {
  return coarse_time_step(opt_.kappa, scene_.rho0, coarse_.spacing, scene_.max_viscosity(), v_.cwiseAbs().maxCoeff());
}

}  // namespace closurelab
