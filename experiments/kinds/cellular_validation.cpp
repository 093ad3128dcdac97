#include "experiments/kinds/cellular_validation.hpp"

#include <chrono>
#include <cmath>

#include "core/averaging/averaging.hpp"
#include "core/base/metrics.hpp"
#include "core/scenes/analytic.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/validation_row.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

double fitted_cellular_amplitude(const ParticleSystem& ps, double k) {
  double num = 0.0, den = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    const Vec2 phi = cellular_mode(ps.x[a], ps.y[a], k);
    num += ps.vx[a] * phi.x() + ps.vy[a] * phi.y();
    den += phi.squaredNorm();
  }
  return den > 0.0 ? num / den : 0.0;
}

double max_displacement_in_spacings(const Scene& scene, const ParticleSystem& ps) {
  const ParticleSystem start = scene.make_particles();
  double d2 = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    const double dx = scene.box.wrap_dx(ps.x[a] - start.x[a]), dy = scene.box.wrap_dy(ps.y[a] - start.y[a]);
    d2 = std::max(d2, dx * dx + dy * dy);
  }
  return std::sqrt(d2) / scene.dx;
}

json run_cellular_validation(const Scene& scene, const AveragingKernel& kernel, SphRunOptions opt, double spacing) {
  using clock = std::chrono::steady_clock;
  const Scene::CellularMode& mode = scene.cellular_mode.value();
  const double k = mode.wavenumber, scale = scene.analytic_peak;
  const TensorMesh2D mesh = observe_mesh(scene, spacing);  // the doubly periodic box's tensor mesh
  const int nodes = mesh.nx();
  const DirectReference direct = run_direct_reference(scene, kernel, opt, mesh);
  const ParticleSystem& ps = direct.particles;
  const SphRunResult& sph = direct.run;
  json row = validation_row_header(sph, {{"dx", scene.dx},
                                         {"eta", scene.eta},
                                         {"h", scene.h},
                                         {"sound_speed", scene.sound_speed},
                                         {"analytic_peak", scale},
                                         {"particle_mass", scene.particle_mass()},
                                         {"wavenumber", k},
                                         {"steady_amplitude", mode.steady_amplitude},
                                         {"initial_amplitude", mode.initial_amplitude},
                                         {"decay_rate", mode.decay_rate},
                                         {"mesh_nodes_per_side", nodes}});
  if (sph.status == Status::numerical_issue) return row;

  // Particles against the exact field at the final time.
  const double amp = mode.amplitude(sph.time), fitted = fitted_cellular_amplitude(ps, k);
  json errors;
  errors["amplitude"] = {{"fitted", fitted},
                         {"analytic", amp},
                         {"relative_difference", amp != 0.0 ? (fitted - amp) / amp : fitted / scale}};
  errors["particles_vs_analytic"] =
      particles_vs_field(ps, [&](double x, double y) { return Vec2(amp * cellular_mode(x, y, k)); }, scale);

  // Gaussian averages on the mesh: a separable even window multiplies the mode by its 2D symbol at
  // (k, k) / 2π (for the Gaussian, exp(−|k|² η² / 4) with |k|² = 2k²).
  const auto t_avg = clock::now();
  const MesoFields f = average_particles(ps, scene.box, kernel, mesh, AveragingRequest{});
  const double factor = kernel.symbol(Vec2(k, k) / (2.0 * M_PI));
  Eigen::VectorXd ax(mesh.size()), ay(mesh.size());
  for (int n = 0; n < mesh.size(); ++n) {
    const Vec2 v = factor * amp * cellular_mode(mesh.node(n).x(), mesh.node(n).y(), k);
    ax[n] = v.x(), ay[n] = v.y();
  }
  errors["averaged_vs_averaged_analytic"] = vector_error_norms(f.vx, f.vy, ax, ay, scale).to_json();
  errors["averaging_factor"] = factor;
  errors["max_displacement_dx"] = max_displacement_in_spacings(scene, ps);
  row["errors"] = errors;
  const double avg_seconds = std::chrono::duration<double>(clock::now() - t_avg).count();
  row["cost"] = sph.cost_json(avg_seconds);
  row["cost"]["peak_memory_mib"] = peak_memory_mib();
  return row;
}

}  // namespace closurelab
