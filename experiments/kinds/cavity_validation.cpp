#include "experiments/kinds/cavity_validation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/base/errors.hpp"
#include "core/scenes/ghia_cavity.hpp"
#include "core/sph/sph_engine.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/validation_row.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

Vec2 shepard_velocity(const ParticleSystem& ps, const Scene& scene, double x, double y) {
  const SmoothingKernel w = scene.smoothing_kernel();
  const double support2 = w.support() * w.support();
  double sw = 0.0, su = 0.0, sv = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const double dx = x - ps.x[a], dy = y - ps.y[a], r2 = dx * dx + dy * dy;
    if (r2 >= support2) continue;
    const double wa = w.w(std::sqrt(r2));
    sw += wa, su += wa * ps.vx[a], sv += wa * ps.vy[a];
  }
  return sw > 0.0 ? Vec2(su / sw, sv / sw) : Vec2(0.0, 0.0);
}

namespace {

// u at Ghia's y on x = L/2 and v at Ghia's x on y = L/2, in units of the lid speed, from particles in the scene's
// coordinates (the cavity's corner at (origin, origin)).
struct Centrelines {
  std::vector<double> u, v;
};

Centrelines centrelines(const ParticleSystem& ps, const Scene& scene, const GhiaCentrelines& ghia) {
  const Scene::LidDrivenCavity& c = scene.cavity.value();
  Centrelines out;
  for (int k = 0; k < GhiaCentrelines::kPoints; ++k) {
    out.u.push_back(shepard_velocity(ps, scene, c.origin + 0.5 * c.side, c.origin + ghia.y[k] * c.side).x() / c.lid_speed);
    out.v.push_back(shepard_velocity(ps, scene, c.origin + ghia.x[k] * c.side, c.origin + 0.5 * c.side).y() / c.lid_speed);
  }
  return out;
}

// The largest |a − b| over Ghia's points inside the cavity (those on the walls are the boundary conditions, which
// an interpolation across the wall surface blurs).
double largest_difference(const std::vector<double>& a, const std::vector<double>& b,
                          const std::array<double, GhiaCentrelines::kPoints>& coordinate) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (coordinate[k] > 0.0 && coordinate[k] < 1.0) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

}  // namespace

json run_cavity_validation(const json& cfg, const Scene& scene, const AveragingKernel& kernel, double observe_spacing,
                           const std::function<void(const std::string&)>& progress) {
  const Scene::LidDrivenCavity& cavity = scene.cavity.value();
  const GhiaCentrelines ghia = ghia_centrelines(cavity.reynolds).value();
  const SphRunOptions opt = sph_run_options_from(cfg.at("solver"));
  const StoredReference direct = stored_transient_reference(cfg, scene, kernel, observe_spacing, progress);
  const ParticleSystem& ps = direct.particles;
  const SphRunResult sph = SphRunResult::from_json(direct.run);
  json row = validation_row_header(sph, {{"dx", scene.dx},
                                         {"h", scene.h},
                                         {"sound_speed", scene.sound_speed},
                                         {"particle_mass", scene.particle_mass()},
                                         {"kinematic_viscosity", scene.phase_viscosity[0] / scene.rho0},
                                         {"reynolds", cavity.reynolds},
                                         {"wall_thickness", cavity.origin},
                                         {"formulation", name_of(opt.engine.formulation)}});
  row["direct_sph"] = direct.run;  // with its reference_store record
  if (sph.status == Status::numerical_issue) return row;
  // The profiles at the end, and their mean over the last five saved times (t = 0.8, 0.85, ..., 1 × the target
  // time; PySPH's cavity.py averages its last five outputs likewise): the particles' velocities fluctuate about the
  // steady flow, which the mean estimates.
  const std::vector<ParticleSnapshot>& snaps = direct.snapshots;
  const std::size_t window = std::min<std::size_t>(5, snaps.size());
  Centrelines mean{std::vector<double>(GhiaCentrelines::kPoints, 0.0), std::vector<double>(GhiaCentrelines::kPoints, 0.0)};
  std::vector<Centrelines> last;
  for (std::size_t k = snaps.size() - window; k < snaps.size(); ++k) {
    last.push_back(centrelines(snaps[k].particles, scene, ghia));
    for (int q = 0; q < GhiaCentrelines::kPoints; ++q)
      mean.u[q] += last.back().u[q] / window, mean.v[q] += last.back().v[q] / window;
  }
  const Centrelines end = centrelines(ps, scene, ghia);
  const std::vector<double> gu(ghia.u.begin(), ghia.u.end()), gv(ghia.v.begin(), ghia.v.end());
  const double du = largest_difference(mean.u, gu, ghia.y), dv = largest_difference(mean.v, gv, ghia.x);
  const double du_end = largest_difference(end.u, gu, ghia.y), dv_end = largest_difference(end.v, gv, ghia.x);
  // How steady the window is: the largest change of the profiles between successive saved times in it.
  double change = 0.0;
  for (std::size_t k = 1; k < last.size(); ++k)
    change = std::max({change, largest_difference(last[k].u, last[k - 1].u, ghia.y),
                       largest_difference(last[k].v, last[k - 1].v, ghia.x)});
  json errors;
  errors["centrelines"] = {{"reference", "Ghia, Ghia & Shin, J. Comput. Phys. 48 (1982) 387-411, Tables I and II"},
                           {"mean_over_times", window ? json(std::vector<double>{snaps[snaps.size() - window].time,
                                                                                snaps.back().time})
                                                      : json(nullptr)},
                           {"y", ghia.y},
                           {"u_ghia", ghia.u},
                           {"u", mean.u},
                           {"u_end", end.u},
                           {"x", ghia.x},
                           {"v_ghia", ghia.v},
                           {"v", mean.v},
                           {"v_end", end.v},
                           {"max_abs_u", du},
                           {"max_abs_v", dv},
                           {"worst", std::max(du, dv)},
                           {"worst_end", std::max(du_end, dv_end)},
                           {"largest_change_between_saved_times", change}};
  // The disorder: the spread of the fluid's summation number density at the end.
  errors["number_density"] = number_density_spread(scene, ps, opt.engine);
  row["errors"] = errors;
  row["cost"] = sph.cost_json(0.0);
  row["cost"]["peak_memory_mib"] = peak_memory_mib();
  return row;
}

}  // namespace closurelab
