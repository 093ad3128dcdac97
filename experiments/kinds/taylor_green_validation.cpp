#include "experiments/kinds/taylor_green_validation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/averaging/averaging.hpp"
#include "core/base/metrics.hpp"
#include "core/sph/sph_engine.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/validation_row.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

json run_taylor_green_validation(const json& cfg, const Scene& scene, const AveragingKernel& kernel,
                                 double observe_spacing, const std::function<void(const std::string&)>& progress) {
  const Scene::TaylorGreenVortex& tg = scene.taylor_green.value();
  const SphRunOptions opt = sph_run_options_from(cfg.at("solver"));
  const StoredReference direct = stored_transient_reference(cfg, scene, kernel, observe_spacing, progress);
  const ParticleSystem& ps = direct.particles;
  const SphRunResult sph = SphRunResult::from_json(direct.run);
  json times = json::array(), computed = json::array(), exact = json::array(), relative = json::array();
  double worst = 0.0, last = 0.0;
  for (const ParticleSnapshot& snap : direct.snapshots) {
    double v2 = 0.0;
    for (std::size_t a = 0; a < snap.particles.size(); ++a)
      if (!snap.particles.fixed[a])
        v2 = std::max(v2, snap.particles.vx[a] * snap.particles.vx[a] + snap.particles.vy[a] * snap.particles.vy[a]);
    const double t = snap.time, v = std::sqrt(v2), e = tg.max_speed(t), err = std::abs(v - e) / e;
    times.push_back(t);
    computed.push_back(v);
    exact.push_back(e);
    relative.push_back(err);
    worst = std::max(worst, err);
    last = err;
  }
  json row = validation_row_header(sph, {{"dx", scene.dx},
                                         {"h", scene.h},
                                         {"sound_speed", scene.sound_speed},
                                         {"particle_mass", scene.particle_mass()},
                                         {"kinematic_viscosity", scene.phase_viscosity[0] / scene.rho0},
                                         {"decay_rate", tg.decay_rate},
                                         {"formulation", name_of(opt.engine.formulation)}});
  row["direct_sph"] = direct.run;  // with its reference_store record
  if (sph.status == Status::numerical_issue) return row;
  json errors;
  errors["max_speed"] = {{"times", times},           {"computed", computed}, {"exact", exact},
                         {"relative_error", relative}, {"worst", worst},       {"final", last}};
  // The reference a reduced model of the transient is scored against: the particles averaged onto the averaging
  // mesh at each saved time, against the exact field averaged (a separable even window multiplies the mode by its
  // symbol at (k, k) / 2π), relative to the averaged field's largest speed.
  const TensorMesh2D mesh = observe_mesh(scene, observe_spacing);
  const double window = kernel.symbol(Vec2(tg.wavenumber, tg.wavenumber) / (2.0 * M_PI));
  json avg_max = json::array(), avg_l2 = json::array();
  double avg_worst = 0.0;
  const auto t_avg = std::chrono::steady_clock::now();
  for (const ParticleSnapshot& snap : direct.snapshots) {
    const MesoFields f = average_particles(snap.particles, scene.box, kernel, mesh, AveragingRequest{});
    Eigen::VectorXd ax(mesh.size()), ay(mesh.size());
    for (int n = 0; n < mesh.size(); ++n) {
      const Vec2 v = window * tg.velocity_at(mesh.node(n).x(), mesh.node(n).y(), snap.time);
      ax[n] = v.x(), ay[n] = v.y();
    }
    const ErrorNorms e = vector_error_norms(f.vx, f.vy, ax, ay, window * tg.max_speed(snap.time));
    avg_max.push_back(e.max_rel);
    avg_l2.push_back(e.l2_rel);
    avg_worst = std::max(avg_worst, e.max_rel);
  }
  const double avg_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_avg).count();
  errors["averaged_vs_averaged_exact"] = {{"times", times},         {"max_rel", avg_max},
                                          {"l2_rel", avg_l2},       {"worst_max_rel", avg_worst},
                                          {"window_factor", window}, {"mesh_nodes_per_side", mesh.nx()}};
  // The particles against the exact field at the end, relative to its largest speed.
  errors["particles_vs_exact"] = particles_vs_field(
      ps, [&](double x, double y) { return tg.velocity_at(x, y, sph.time); }, tg.max_speed(sph.time));
  // The disorder: the spread of the summation number density at the end (on the lattice it is uniform).
  errors["number_density"] = number_density_spread(scene, ps, opt.engine);
  row["errors"] = errors;
  row["cost"] = sph.cost_json(avg_seconds);
  row["cost"]["peak_memory_mib"] = peak_memory_mib();
  return row;
}

}  // namespace closurelab
