#include "experiments/kinds/coarse_continuum_scoring.hpp"

#include <algorithm>
#include <cmath>

#include "core/averaging/averaging.hpp"
#include "core/base/metrics.hpp"
#include "core/scenes/ghia_cavity.hpp"

namespace closurelab {

NodeVelocity mode_shape(const Scene& s, const TensorMesh2D& mesh) {
  NodeVelocity f{Eigen::VectorXd(mesh.size()), Eigen::VectorXd(mesh.size())};
  for (int n = 0; n < mesh.size(); ++n) {
    const Vec2 q = mesh.node(n);
    if (s.taylor_green) {
      const double k = s.taylor_green->wavenumber;
      f.x[n] = -std::cos(k * q.x()) * std::sin(k * q.y());
      f.y[n] = std::sin(k * q.x()) * std::cos(k * q.y());
    } else {
      const double k = s.cellular_mode->wavenumber;
      f.x[n] = std::sin(k * q.x()) * std::cos(k * q.y());
      f.y[n] = -std::cos(k * q.x()) * std::sin(k * q.y());
    }
  }
  return f;
}

double mode_amplitude(const Scene& s, double t) {
  return s.taylor_green ? s.taylor_green->factor(t) : s.cellular_mode->amplitude(t);
}

double mode_wavenumber(const Scene& s) {
  return s.taylor_green ? s.taylor_green->wavenumber : s.cellular_mode->wavenumber;
}

std::vector<int> interior_nodes(const Scene& s, const TensorMesh2D& mesh) {
  std::vector<int> out;
  if (!s.cavity) return out;
  const double lo = s.cavity->origin + 3.0 * s.eta, hi = s.cavity->origin + s.cavity->side - 3.0 * s.eta;
  for (int n = 0; n < mesh.size(); ++n) {
    const Vec2 q = mesh.node(n);
    if (q.x() >= lo && q.x() <= hi && q.y() >= lo && q.y() <= hi) out.push_back(n);
  }
  return out;
}

NodeVelocity averaged_baseline(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh,
                               const ContinuumNavierStokes2D& baseline) {
  ParticleSystem ps = scene.make_particles();  // the walls at their prescribed velocity
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    const Eigen::Vector2d v = baseline.velocity_at(ps.x[a], ps.y[a]);
    ps.vx[a] = v.x();
    ps.vy[a] = v.y();
  }
  const MesoFields f = average_particles(ps, scene.box, kernel, mesh, AveragingRequest{});
  return NodeVelocity{f.vx, f.vy};
}

namespace {

json ghia_comparison(const Scene& scene, const ContinuumNavierStokes2D& baseline) {
  if (!scene.cavity) return nullptr;
  const Scene::LidDrivenCavity& c = *scene.cavity;
  const std::optional<GhiaCentrelines> table = ghia_centrelines(c.reynolds);
  if (!table) return nullptr;
  const GhiaCentrelines& g = *table;
  std::vector<double> u, v;
  double du = 0.0, dv = 0.0;
  for (int k = 0; k < GhiaCentrelines::kPoints; ++k) {
    u.push_back(baseline.velocity_at(c.origin + 0.5 * c.side, c.origin + g.y[k] * c.side).x() / c.lid_speed);
    v.push_back(baseline.velocity_at(c.origin + g.x[k] * c.side, c.origin + 0.5 * c.side).y() / c.lid_speed);
    if (g.y[k] > 0.0 && g.y[k] < 1.0) du = std::max(du, std::abs(u.back() - g.u[k]));
    if (g.x[k] > 0.0 && g.x[k] < 1.0) dv = std::max(dv, std::abs(v.back() - g.v[k]));
  }
  return {{"reference", "Ghia, Ghia & Shin, J. Comput. Phys. 48 (1982) 387-411, Tables I and II"},
          {"y", g.y},
          {"u_ghia", g.u},
          {"u", u},
          {"x", g.x},
          {"v_ghia", g.v},
          {"v", v},
          {"max_abs_u", du},
          {"max_abs_v", dv},
          {"worst", std::max(du, dv)}};
}

}  // namespace

bool replay_baseline_views(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh,
                           ContinuumNavierStokes2D& baseline, const std::vector<double>& times, double target,
                           BaselineViews& out) {
  for (double t : times) {
    if (t > target) break;
    if (!baseline.advance_to(t)) return false;
    out.at_times.push_back(averaged_baseline(scene, kernel, mesh, baseline));
  }
  if (!baseline.advance_to(target)) return false;
  out.at_target = averaged_baseline(scene, kernel, mesh, baseline);
  out.centrelines = ghia_comparison(scene, baseline);
  return true;
}

json worst_over_saved_times(const json& transient) {
  json worst = json::object();
  for (const char* key : {"baseline_vs_averaged_direct_sph", "averaged_baseline_vs_averaged_direct_sph",
                          "direct_sph_vs_averaged_fine_continuum"}) {
    worst[key] = json::object();
    for (const json& snap : transient)
      if (snap.contains(key))
        for (const char* region : {"all_nodes", "interior_nodes"})
          if (snap[key].contains(region))
            worst[key][region] = std::max(worst[key].value(region, 0.0), snap[key][region]["max_rel"].get<double>());
  }
  return worst;
}

bool walled_views(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh,
                  CoarseNavierStokes2DOptions options, const std::vector<double>& times, double target, double scale,
                  BaselineViews& coarse, BaselineViews& fine, json& fields, json& errors) {
  const auto finer = [](const UniformMesh1D& a) {
    return UniformMesh1D::cell_centred(a.origin - 0.5 * a.spacing, a.spacing * a.count,
                                       a.count * kFineContinuumRefinement, a.periodic);
  };
  const TensorMesh2D fine_mesh{finer(mesh.x), finer(mesh.y)};
  auto ns = continuum_baseline_for(scene, mesh, options);
  auto fine_ns = continuum_baseline_for(scene, fine_mesh, options);
  ns->set_velocity(Eigen::VectorXd::Zero(mesh.size()), Eigen::VectorXd::Zero(mesh.size()));
  fine_ns->set_velocity(Eigen::VectorXd::Zero(fine_mesh.size()), Eigen::VectorXd::Zero(fine_mesh.size()));
  if (!replay_baseline_views(scene, kernel, mesh, *ns, times, target, coarse) ||
      !replay_baseline_views(scene, kernel, mesh, *fine_ns, times, target, fine))
    return false;
  fields["averaged_baseline"] = field_json(coarse.at_target);
  fields["averaged_fine_continuum"] = field_json(fine.at_target);
  if (!coarse.centrelines.is_null()) errors["centrelines"] = coarse.centrelines;
  if (!fine.centrelines.is_null()) errors["fine_continuum_centrelines"] = fine.centrelines;
  errors["averaged_baseline_vs_averaged_fine_continuum"] =
      norms(coarse.at_target, fine.at_target, scale, interior_nodes(scene, mesh));
  return true;
}

}  // namespace closurelab
