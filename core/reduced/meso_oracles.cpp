// The reduced model's oracle substitution (the error budget) and its reported wall-surface values
// (core/reduced/meso_solver.hpp: MesoOracles, MesoSolverOptions::wall_node_value).
#include <cmath>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/reduced/meso_solver.hpp"

namespace closurelab {

namespace {
TensorMesh2D as_line(const UniformMesh1D& axis) { return TensorMesh2D{axis, UniformMesh1D{0.0, 1.0, 1, false, 0.0}}; }
}  // namespace

void MesoSolver::set_oracles(MesoOracles oracles) {
  const int n = coarse_.count;
  if (oracles.boundary != BoundaryOracle::none && periodic_)
    throw ConfigError("/oracle/boundary", "the scene has no walls: there is no boundary to hold");
  if ((oracles.closure || oracles.boundary != BoundaryOracle::none) && oracles.averaged.size() != n)
    throw ConfigError("/oracle", "the averaged direct solution must be given at every coarse node");
  if (oracles.positions) {
    if (opt_.balance != MesoBalance::force_density)
      throw ConfigError("/oracle/positions", "the positions oracle re-probes the force-density balance's map: it needs "
                                             "solver.balance = force_density");
    force_density_map_ = fluid_force_density_map_at(scene_, kernel_, coarse_, *oracles.positions);
    // ρ̄ (2.8) and F̄ (2.14) of those particles as x-averages: on one column per lattice column, averaged over x
    // (the lattice's own path takes the column at x = 0 of a strip whose rows are uniform in x).
    AveragingRequest req;
    req.external = true;
    const TensorMesh2D columns{UniformMesh1D{0.0, scene_.dx, scene_.nx, true, scene_.box.lx}, coarse_};
    const MesoFields f = average_particles(*oracles.positions, scene_.box, kernel_, columns, req, {}, scene_.force_x);
    rho_bar_ = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd fx = Eigen::VectorXd::Zero(n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < columns.nx(); ++i) {
        rho_bar_[j] += f.rho[columns.index(i, j)] / columns.nx();
        fx[j] += f.fx[columns.index(i, j)] / columns.nx();
      }
    accel_force_ = fx.cwiseQuotient(rho_bar_);
  }
  if (oracles.boundary != BoundaryOracle::none) {
    const double band = oracles.boundary == BoundaryOracle::wall_band ? 3.0 * kernel_.eta() : 0.0;
    for (int k = 0; k < n; ++k) {
      const double y = coarse_.node(k);
      if (y <= scene_.wall_lo + band - 1e-12 || y >= scene_.wall_hi - band + 1e-12 || k == 0 || k == n - 1) {
        held_[k] = true;
        held_values_[k] = oracles.averaged[k];
      }
    }
  }
  oracle_correction_.reset();
  if (oracles.closure) {
    const auto rows = oracles.row_y.size();
    if (rows < 2 || oracles.row_velocity.size() != oracles.row_y.size())
      throw ConfigError("/oracle/closure", "the direct solution's row velocities are missing");
    const Eigen::VectorXd saved = v_;
    v_ = oracles.averaged;
    std::string issue;
    if (!deconvolve(issue)) throw NumericalError("closure oracle: " + issue);
    std::vector<Vec2> points;
    for (Eigen::Index j = 0; j < oracles.row_y.size(); ++j) points.emplace_back(0.0, oracles.row_y[j]);
    const Eigen::VectorXd at_rows = sample_reconstruction(points).row(0).transpose();
    const double spacing = oracles.row_y[1] - oracles.row_y[0];
    const UniformMesh1D row_axis{oracles.row_y[0], spacing, static_cast<int>(rows), periodic_, scene_.box.ly};
    oracle_correction_.emplace(as_line(row_axis), 1, Eigen::VectorXd(oracles.row_velocity - at_rows));
    v_ = saved;
  }
  oracles_ = std::move(oracles);
  hold_nodes();
  integrator_.reset();  // held nodes and the closure changed: what the integrator learned of the rate is stale
}

Eigen::VectorXd MesoSolver::reported_velocity() {
  Eigen::VectorXd v = v_;
  if (periodic_ || walls_are_data_ || opt_.wall_node_value == WallNodeValue::imposed || oracles_.boundary != BoundaryOracle::none) return v;
  std::string issue;
  if (!deconvolve(issue)) return v;
  // v̄ at a wall-surface node as (2.9) of the lattice column: Σ_rows φ(y − y_j) V_j / Σ_rows φ(y − y_j), every
  // lattice row in the sums (wall rows at rest).
  const double r = kernel_.support_radius();
  for (int k : {0, coarse_.count - 1}) {
    const double y = coarse_.node(k);
    std::vector<Vec2> points;
    std::vector<double> weights;
    double total = 0.0;
    for (int j = static_cast<int>(std::floor((y - r) / scene_.dx)); j <= static_cast<int>(std::ceil((y + r) / scene_.dx)); ++j) {
      const double yj = (j + 0.5) * scene_.dx;
      if (yj < 0.0 || yj > scene_.box.ly) continue;
      const double w = kernel_.factor(y - yj);
      total += w;
      points.emplace_back(0.0, yj);
      weights.push_back(w);
    }
    const Eigen::Matrix2Xd vs = sample_reconstruction(points);
    double sum = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) sum += weights[i] * vs(0, static_cast<Eigen::Index>(i));
    v[k] = sum / total;
  }
  return v;
}

}  // namespace closurelab
