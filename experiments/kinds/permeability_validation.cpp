#include "experiments/kinds/permeability_validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/sph/sph_engine.hpp"
#include "experiments/kinds/cellular_validation.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

double darcy_permeability(const Scene& scene, const ParticleSystem& ps) {
  const Scene::Permeability& perm = scene.permeability.value();
  double sum = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) sum += ps.vx[a];
  const double mean = sum * scene.dx * scene.dx / (scene.box.lx * scene.box.ly);
  return scene.phase_viscosity.at(0) * mean / (scene.rho0 * perm.body_force);
}

namespace {

// The largest distance of a moving particle from the nearest site of the lattice (i + 1/2, j + 1/2) ε', in ε':
// how far the fluid has left the lattice arrangement (at most √2/2), as opposed to how far it has travelled.
double max_distance_from_lattice(const Scene& scene, const ParticleSystem& ps) {
  double d2 = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    const double u = ps.x[a] / scene.dx - 0.5, v = ps.y[a] / scene.dx - 0.5;
    const double du = u - std::nearbyint(u), dv = v - std::nearbyint(v);
    d2 = std::max(d2, du * du + dv * dv);
  }
  return std::sqrt(d2);
}

}  // namespace

json run_permeability_validation(const Scene& scene, SphRunOptions opt) {
  const Scene::Permeability& perm = scene.permeability.value();
  ParticleSystem ps = scene.make_particles();
  std::int64_t fluid = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) fluid += !ps.fixed[a];
  // Steady state by the permeability itself: the observable is k, a single number; the time loop compares it
  // every steady_window steps. Each observation is kept (the first at t = 0).
  std::vector<double> history;
  opt.observable = [&](const ParticleSystem& p) {
    history.push_back(darcy_permeability(scene, p));
    return Eigen::VectorXd::Constant(1, history.back());
  };
  const SphRunResult sph = run_direct_sph(scene, ps, opt);
  json row;
  row["status"] = row_status(sph.status);
  row["direct_sph"] = sph.to_json();
  if (!sph.message.empty()) row["message"] = sph.message;
  const double rho = scene.rho0, mu = scene.phase_viscosity.at(0), nu = mu / rho;
  row["scene_derived"] = {{"dx", scene.dx},
                          {"eta", scene.eta},
                          {"h", scene.h},
                          {"sound_speed", scene.sound_speed},
                          {"particle_mass", scene.particle_mass()},
                          {"solid_fraction", perm.solid_fraction},
                          {"solid_size", perm.solid_size},
                          {"fluid_particles", fluid},
                          {"solid_particles", static_cast<std::int64_t>(ps.size()) - fluid},
                          {"lattice_solid_fraction", 1.0 - static_cast<double>(fluid) / static_cast<double>(ps.size())},
                          {"reference_permeability", perm.reference},
                          {"reference_source", perm.reference_source},
                          {"reference_superficial_velocity", perm.superficial_velocity(rho, mu)},
                          {"viscous_time_k_over_nu", perm.reference / nu}};
  if (sph.status == Status::numerical_issue) return row;

  const double k = darcy_permeability(scene, ps);
  json errors;
  errors["permeability"] = {{"sph", k},
                            {"reference", perm.reference},
                            {"relative_difference", (k - perm.reference) / perm.reference},
                            {"over_l2", k / (scene.box.lx * scene.box.ly)},
                            {"reference_over_l2", perm.reference / (scene.box.lx * scene.box.ly)}};
  if (perm.solid_size_for) {
    const double eff = perm.solid_size_for(k);
    errors["effective_solid_size"] = {
        {"size", eff}, {"nominal", perm.solid_size}, {"shift_in_spacings", (perm.solid_size - eff) / scene.dx}};
  }
  // The k history: one value every steady_window steps (steps = index * window, t ~ steps * dt).
  errors["permeability_history"] = {
      {"window_steps", opt.steady_window}, {"window_time", opt.steady_window * sph.dt}, {"k", history}};
  double vmax = 0.0, vy_abs = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    vmax = std::max(vmax, std::hypot(ps.vx[a], ps.vy[a]));
    vy_abs = std::max(vy_abs, std::abs(ps.vy[a]));
  }
  const double u_mean = rho * perm.body_force * k / mu;
  errors["flow"] = {{"superficial_velocity", u_mean},
                    {"max_speed", vmax},
                    {"max_abs_vy", vy_abs},
                    {"reynolds_a_u_over_nu", perm.solid_size * u_mean / nu},
                    {"reynolds_l_u_over_nu", scene.box.lx * u_mean / nu},
                    {"mach_max_speed_over_c", vmax / scene.sound_speed}};
  // The particles: largest displacement from the initial lattice site (how far they travelled) and from the
  // nearest lattice site (how far they left the lattice), in ε'; the density deviation m n / ρ0 − 1 of the fluid.
  errors["max_displacement_dx"] = max_displacement_in_spacings(scene, ps);
  errors["max_distance_from_lattice_dx"] = max_distance_from_lattice(scene, ps);
  {
    ParticleSystem probe = ps;
    SphEngine engine(scene, probe, opt.engine);
    engine.compute_accelerations();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t a = 0; a < ps.size(); ++a) {
      if (ps.fixed[a]) continue;
      const double dev = ps.mass[a] * engine.number_density()[a] / rho - 1.0;
      lo = std::min(lo, dev), hi = std::max(hi, dev);
    }
    errors["density_deviation"] = {{"min", lo}, {"max", hi}};
  }
  row["errors"] = errors;
  row["cost"] = sph.cost_json(0.0);
  row["cost"]["peak_memory_mib"] = peak_memory_mib();
  return row;
}

}  // namespace closurelab
