#pragma once
// What the direct SPH validations of the doubly periodic scenes share (cellular_validation.cpp,
// taylor_green_validation.cpp): the row's header from the run, and the moving particles against an exact field.
#include <functional>
#include <vector>

#include "core/base/metrics.hpp"
#include "core/base/params.hpp"
#include "core/sph/particles.hpp"
#include "core/sph/sph_run.hpp"
#include "core/base/status.hpp"

namespace closurelab {

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

}  // namespace closurelab
