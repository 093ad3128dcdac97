#include "core/continuum/continuum_navier_stokes_2d.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/base/errors.hpp"
#include "core/continuum/cavity_navier_stokes_2d.hpp"
#include "core/continuum/coarse_navier_stokes_2d.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

Eigen::VectorXd ContinuumNavierStokes2D::ab2(const Eigen::VectorXd& v, const Eigen::VectorXd& r,
                                             const Eigen::VectorXd& r_prev, double dt, double dt_prev) {
  if (!(dt_prev > 0.0)) return v + dt * r;
  const double w = dt / dt_prev;
  return v + dt * ((1.0 + 0.5 * w) * r - 0.5 * w * r_prev);
}

bool ContinuumNavierStokes2D::advance_to(double t) {
  while (time_ < t) {
    const double remaining = t - time_;
    // Equal steps to t under the current limit, so that the last one is not a sliver (AB2's ω stays near 1).
    const double count = std::max(1.0, std::ceil(remaining / time_step() - 1e-9));
    if (!step(remaining / count)) return false;
    if (count == 1.0) time_ = t;
  }
  return true;
}

TensorMesh2D continuum_mesh_for(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta) {
  if (!scene.cavity) return coarse_mesh_2d(scene, kernel, spacing_over_eta);
  const Scene::LidDrivenCavity& c = *scene.cavity;
  const int cells = static_cast<int>(std::lround(c.side / (spacing_over_eta * scene.eta)));
  if (cells < 4)
    throw ConfigError("/solver/spacing_over_eta", "the cavity's side holds " + std::to_string(cells) +
                                                      " cells of this spacing; at least 4 are needed");
  const UniformMesh1D axis = UniformMesh1D::cell_centred(c.origin, c.side, cells, false);
  return {axis, axis};
}

std::unique_ptr<ContinuumNavierStokes2D> continuum_baseline_for(const Scene& scene, const TensorMesh2D& mesh,
                                                                CoarseNavierStokes2DOptions options,
                                                                const AveragingKernel* average_force) {
  if (!scene.cavity) return coarse_navier_stokes_for(scene, mesh, options, average_force);
  if (scene.phase_viscosity.size() != 1)
    throw std::invalid_argument("the cavity baseline needs one phase; scene '" + scene.name + "' has several");
  return std::make_unique<CavityNavierStokes2D>(mesh, scene.rho0, scene.phase_viscosity[0], scene.cavity->lid_speed,
                                                options);
}

}  // namespace closurelab
