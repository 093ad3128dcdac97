#include "core/sph/sph_run.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <numbers>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/option_table.hpp"
#include "core/base/time_loop.hpp"
#include "core/sph/linearised_steady.hpp"
#include "core/sph/sph_engine.hpp"

namespace closurelab {

json SphRunResult::to_json() const {
  json j = TimeLoopResult::to_json();
  j["moving_particles"] = moving_particles;
  j["active_particles"] = active_particles;
  j["total_particles"] = total_particles;
  j["particle_steps"] = static_cast<double>(moving_particles) * static_cast<double>(steps);
  j["pair_evaluations"] = pair_evaluations;
  j["list_rebuilds"] = list_rebuilds;
  return j;
}

json SphRunResult::cost_json(double averaging_seconds) const {
  const double particle_steps = static_cast<double>(moving_particles) * steps;
  return {{"wall_seconds", wall_seconds},
          {"averaging_seconds", averaging_seconds},
          {"steps", steps},
          {"dt", dt},
          {"model_time", time},
          {"particle_steps", particle_steps},
          {"particle_steps_per_second", wall_seconds > 0 ? particle_steps / wall_seconds : 0.0},
          {"pair_evaluations", pair_evaluations}};
}

SphRunResult SphRunResult::from_json(const json& j) {
  SphRunResult r;
  r.status = parse_name<Status>(j.at("status").get<std::string>(), "/status");
  r.steps = j.at("steps").get<std::int64_t>();
  r.time = j.at("time").get<double>();
  r.dt = j.at("dt").get<double>();
  r.wall_seconds = j.at("wall_seconds").get<double>();
  r.cpu_seconds = j.value("cpu_seconds", 0.0);  // 0: an entry stored before CPU time was recorded
  r.last_relative_change = j.at("last_relative_change").get<double>();
  r.moving_particles = j.at("moving_particles").get<std::int64_t>();
  r.active_particles = j.at("active_particles").get<std::int64_t>();
  r.total_particles = j.at("total_particles").get<std::int64_t>();
  r.pair_evaluations = j.at("pair_evaluations").get<std::int64_t>();
  r.list_rebuilds = j.at("list_rebuilds").get<std::int64_t>();
  r.message = j.value("message", "");
  return r;
}

namespace {

SphRunResult linearised_steady_run(const Scene& scene, ParticleSystem& ps, const SphRunOptions& opt) {
  const auto cpu0 = std::clock();
  const LinearisedSteadyResult r = solve_linearised_steady(scene, ps);
  SphRunResult res;
  res.status = r.converged ? Status::converged : Status::numerical_issue;
  res.message = r.message;
  res.wall_seconds = r.seconds();
  res.cpu_seconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  res.last_relative_change = r.relative_residual;
  res.total_particles = static_cast<std::int64_t>(ps.size());
  for (std::size_t a = 0; a < ps.size(); ++a) res.moving_particles += ps.fixed[a] ? 0 : 1;
  res.active_particles = res.total_particles;
  if (opt.progress)
    opt.progress("direct SPH: linearised steady state, " + std::to_string(r.velocity_unknowns + r.density_unknowns) +
                 " unknowns, " + std::to_string(r.nonzeros) + " nonzeros, " + std::to_string(r.seconds()) +
                 " s (assembly " + std::to_string(r.assemble_seconds) + ", factor " +
                 std::to_string(r.factor_seconds) + ", solve " + std::to_string(r.solve_seconds) + ")");
  if (opt.observable && r.converged) opt.observable(ps);
  return res;
}

}  // namespace

SphRunResult run_direct_sph(const Scene& scene, ParticleSystem& ps, const SphRunOptions& opt) {
  if (opt.method == SphMethod::linearised_steady) return linearised_steady_run(scene, ps, opt);
  SphEngine engine(scene, ps, opt.engine);
  engine.compute_accelerations();
  SteppedModel model;
  model.name = "direct SPH";
  model.time_step = [&] { return engine.time_step(opt.kappa); };
  model.step = [&](double dt, std::string&) {
    engine.step(dt);
    return true;
  };
  model.observe = [&]() -> Eigen::VectorXd {
    if (opt.observable) return opt.observable(ps);
    Eigen::VectorXd v(engine.moving().size());
    for (std::size_t k = 0; k < engine.moving().size(); ++k) v[k] = ps.vx[engine.moving()[k]];
    return v;
  };
  model.check_state = [&](std::string& issue) {
    for (int a : engine.moving())
      if (!std::isfinite(ps.vx[a]) || !std::isfinite(ps.vy[a]) || !std::isfinite(ps.x[a]) || !std::isfinite(ps.y[a])) {
        issue = "non-finite particle state";
        return false;
      }
    return true;
  };
  if (opt.on_snapshot) model.snapshot = [&](double t) { opt.on_snapshot(t, ps); };
  model.describe = [&] {
    std::ostringstream os;
    os << "max|v| = " << engine.max_speed();
    return os.str();
  };
  SphRunResult res;
  static_cast<TimeLoopResult&>(res) = run_time_loop(model, opt);
  res.total_particles = static_cast<std::int64_t>(ps.size());
  res.moving_particles = static_cast<std::int64_t>(engine.moving().size());
  res.pair_evaluations = engine.pair_evaluations();
  res.list_rebuilds = engine.list_rebuilds();
  res.active_particles = static_cast<std::int64_t>(engine.active_count());
  return res;
}

namespace {

const OptionTable<SphRunOptions>& sph_solver_options() {
  using O = SphRunOptions;
  static const OptionTable<O> table =
      OptionTable<O>("/solver")
          .choice("method", &O::method,
                  "march: time steps of the engine (mode steady or target_time); linearised_steady: the steady state "
                  "on the frozen lattice by one sparse solve of the linearised pair forces and summation density "
                  "(CHOLMOD LDLT under METIS; standard formulation, mode steady, particles on their sites; the fixed "
                  "particles keep their density): the like-for-like comparator of a steady reduced model")
          .number("kappa", &O::kappa, "time-step coefficient kappa of (5.21)-(5.22)", 0.0, 1.0, true)
          .choice("formulation", [](O& o) -> SphFormulation& { return o.engine.formulation; },
                  "standard: weakly compressible SPH, pair force (5.1), velocity Verlet; transport_velocity: Adami, Hu "
                  "& Adams (2013) as PySPH's TVFScheme (particles advected with a transport velocity, extra stress "
                  "rho v (v~ - v), step kappa min(h/(c + U), h^2/(2 nu)); walls and solids by the generalized wall condition of Adami, Hu & Adams 2012)")
          .number("transport_background_pressure_factor",
                  [](O& o) -> double& { return o.engine.transport_background_pressure_factor; },
                  "transport_velocity: background pressure p_b of the transport velocity / (rho0 c^2) (PySPH's pb / p0)",
                  0.0, {}, true)
          .time_loop();
  return table;
}

}  // namespace

ParamSchema sph_solver_schema() { return sph_solver_options().schema(); }

SphRunOptions sph_run_options_from(const json& s) { return sph_solver_options().read(s); }

json upgraded_sph_solver_params(json solver) {
  if (!solver.is_object()) return solver;
  const SphRunOptions d;
  if (!solver.contains("formulation")) solver["formulation"] = std::string(name_of(d.engine.formulation));
  if (!solver.contains("transport_background_pressure_factor"))
    solver["transport_background_pressure_factor"] = d.engine.transport_background_pressure_factor;
  if (!solver.contains("method")) solver["method"] = std::string(name_of(d.method));
  return solver;
}

double direct_step_bound(const Scene& scene, double kappa, SphFormulation formulation) {
  if (formulation == SphFormulation::transport_velocity) {
    const double h = scene.h;
    double dt = 0.5 * scene.rho0 * h * h / scene.max_viscosity();
    if (scene.sound_speed > 0.0) dt = std::min(dt, h / scene.sound_speed);
    return kappa * dt;
  }
  const double dx = scene.dx;
  double dt = scene.rho0 * dx * dx / scene.max_viscosity();
  if (scene.sound_speed > 0.0) dt = std::min(dt, dx / scene.sound_speed);
  return kappa * dt;
}

namespace {
SphFormulation formulation_of(const json& s, const std::string& path) {
  return s.contains("formulation") ? parse_name<SphFormulation>(s.at("formulation").get<std::string>(), path + "/formulation")
                                   : SphFormulation::standard;
}
}  // namespace

void check_run_can_finish(const Scene& scene, const json& s, const std::string& path) {
  check_steps_reach_target(s, direct_step_bound(scene, s.at("kappa").get<double>(), formulation_of(s, path)), path);
}

double steady_reach_spacings(const Scene& scene, double spacing) {
  // A porous medium's slowest mode depends on its solid (none stated): no bound, no check.
  if (scene.permeability || !(spacing > 0.0)) return 0.0;
  // Rate 2 k^2 nu = pi^2 nu / W^2 with W = pi / (sqrt(2) k).
  if (scene.cellular_mode) return std::numbers::pi / (std::sqrt(2.0) * scene.cellular_mode->wavenumber * spacing);
  if (scene.has_walls) return (scene.wall_hi - scene.wall_lo) / spacing;
  // Rate q^2 nu = pi^2 nu / W^2 with W = pi / q.
  if (scene.steady_sine_mode) return std::numbers::pi / (scene.steady_sine_mode->wavenumber * spacing);
  return 0.0;
}

void check_stepped_run(const Scene& scene, const json& s, double spacing, double max_dt, const std::string& path) {
  check_steps_reach_target(s, max_dt, path);
  const double spacings = steady_reach_spacings(scene, spacing);
  if (spacings > 0.0) check_steady_reach(s, spacings, path);
}

void check_direct_run(const Scene& scene, const json& s, const std::string& path) {
  const SphFormulation formulation = formulation_of(s, path);
  if (s.contains("method") &&
      parse_name<SphMethod>(s.at("method").get<std::string>(), path + "/method") == SphMethod::linearised_steady) {
    if (s.contains("mode") && s.at("mode").get<std::string>() != "steady")
      throw ConfigError(path + "/method", "linearised_steady gives the steady state only: set mode to steady");
    if (formulation != SphFormulation::standard)
      throw ConfigError(path + "/method", "linearised_steady linearises the standard formulation's pair forces; got " +
                                              name_of(formulation));
    try {
      check_linearised_steady(scene, "/scene");
    } catch (const ConfigError& e) {
      throw ConfigError(path + "/method", e.message() + " (at " + e.path() + ")");
    }
    return;
  }
  if (formulation == SphFormulation::transport_velocity && scene.wall_model == WallModel::ghost_velocity)
    throw ConfigError(path + "/formulation", "transport_velocity has its own wall condition (Adami, Hu & Adams 2012); "
                                             "scene '" + scene.name + "' asks for ghost-velocity walls: set the "
                                             "scene's wall_model to zero_velocity");
  if (formulation != SphFormulation::transport_velocity && scene.needs_transport_velocity)
    throw ConfigError(path + "/formulation", "scene '" + scene.name + "' is meant for the transport-velocity "
                                             "formulation (its particles travel): set formulation to "
                                             "transport_velocity");
  check_stepped_run(scene, s, scene.dx, direct_step_bound(scene, s.at("kappa").get<double>(), formulation), path);
}

}  // namespace closurelab
