#pragma once
// What the direct SPH validations of the scenes without walls in y share (cellular_validation.cpp,
// taylor_green_validation.cpp, cavity_validation.cpp): the row's header from the run, the moving particles against an
// exact field, and the saved times of a transient reference.
#include <algorithm>
#include <functional>
#include <limits>
#include <vector>

#include "core/base/metrics.hpp"
#include "core/base/params.hpp"
#include "core/sph/particles.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_run.hpp"
#include "core/base/status.hpp"
#include "experiments/kinds/direct_reference.hpp"

namespace closurelab {

// The saved times of a transient's direct reference: target_time k / 20, k = 1, ..., 20.
inline std::vector<double> transient_saved_times(double target_time) {
  constexpr int kSnapshots = 20;
  std::vector<double> times;
  for (int k = 1; k <= kSnapshots; ++k) times.push_back(target_time * k / kSnapshots);
  return times;
}

// A transient's direct reference from the store (computed and stored when absent): the key is the cell's scene,
// kernel and solver sections, `observe_spacing` (absolute) and transient_saved_times of the solver's target_time.
inline StoredReference stored_transient_reference(const json& cfg, const Scene& scene, const AveragingKernel& kernel,
                                                  double observe_spacing,
                                                  const std::function<void(const std::string&)>& progress) {
  const SphRunOptions opt = sph_run_options_from(cfg.at("solver"));
  const ReferenceRequest request{cfg.at("scene"), cfg.at("kernel"), cfg.at("solver"), observe_spacing,
                                 transient_saved_times(opt.target_time)};
  return stored_direct_reference(request, scene, kernel, progress);
}

// The row's status, direct_sph, message (where the run has one) and scene_derived.
inline json validation_row_header(const SphRunResult& sph, json scene_derived) {
  json row;
  row["status"] = row_status(sph.status);
  row["direct_sph"] = sph.to_json();
  if (!sph.message.empty()) row["message"] = sph.message;
  row["scene_derived"] = std::move(scene_derived);
  return row;
}

// The error norms of the moving particles' velocities against `exact(x, y)`, relative to `scale`.
inline json particles_vs_field(const ParticleSystem& ps, const std::function<Vec2(double, double)>& exact,
                               double scale) {
  std::vector<std::size_t> moving;
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) moving.push_back(a);
  const Eigen::Index np = static_cast<Eigen::Index>(moving.size());
  Eigen::VectorXd ux(np), uy(np), rx(np), ry(np);
  for (Eigen::Index i = 0; i < np; ++i) {
    const std::size_t a = moving[i];
    const Vec2 v = exact(ps.x[a], ps.y[a]);
    ux[i] = ps.vx[a], uy[i] = ps.vy[a], rx[i] = v.x(), ry[i] = v.y();
  }
  return vector_error_norms(ux, uy, rx, ry, scale).to_json();
}

// The particles' disorder: the spread of the moving particles' summation number density, (max − min)/mean and
// max |n/mean − 1| (on the lattice it is uniform), computed by the engine of `options` on a copy of `ps`.
inline json number_density_spread(const Scene& scene, const ParticleSystem& ps, const SphEngineOptions& options) {
  ParticleSystem probe = ps;
  SphEngine engine(scene, probe, options);
  engine.compute_accelerations();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
  std::size_t moving = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    const double n = engine.number_density()[a];
    lo = std::min(lo, n), hi = std::max(hi, n), sum += n;
    ++moving;
  }
  const double mean = sum / static_cast<double>(moving);
  return {{"spread_over_mean", (hi - lo) / mean}, {"max_deviation_from_mean", std::max(hi - mean, mean - lo) / mean}};
}

}  // namespace closurelab
