// The cellular-flow scene (DESIGN.md §5, "cellular"): a doubly periodic square box of m x m cells driven by the
// divergence-free force g (sin kx cos ky, −cos kx sin ky), k = 2π m / L, or a Taylor–Green vortex of the same
// shape, forced or decaying. The flow is not x-invariant: the engine takes the whole body force per particle.
#include "core/scenes/cellular_scene.hpp"

#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/registry.hpp"
#include "core/scenes/analytic.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

ParamSchema cellular_schema() {
  ParamSchema schema{
      integer_param("n", 48, "particles per side (epsilon' = L / n)", 8, 4096),
      integer_param("m", 1, "cells per side (k = 2 pi m / L)", 1, 64),
      number_param("l", 1.0, "box side L", 0.0, {}, true),
      number_param("rho", 1.0, "fluid density", 0.0, {}, true),
      number_param("mu", 1.0, "dynamic viscosity", 0.0, {}, true),
      number_param("re", 0.001, "Reynolds number A / (k nu) of the velocity amplitude A (steady, or initial if unforced)",
                   0.0, 10.0, true),
      bool_param("forced", true, "drive with g (sin kx cos ky, -cos kx sin ky), g = 2 k^2 nu A; else no force"),
      string_param("initial", "rest", "rest, or taylor_green: the velocity A (sin kx cos ky, -cos kx sin ky) at t = 0",
                   {"rest", "taylor_green"}),
      number_param("eta_over_l", 1.0 / 16.0, "averaging scale eta'/L", 0.0, 0.5, true),
      number_param("background_pressure_factor", 1.0, "background pressure / (rho c^2)", 0.0, 10.0)};
  const ParamSchema sph = sph_discretization_params();
  schema.insert(schema.end(), sph.begin(), sph.end());
  return schema;
}

std::unique_ptr<Scene> make_cellular(const json& p) {
  auto s = std::make_unique<Scene>();
  s->name = "cellular";
  s->params = p;
  const int n = p.at("n").get<int>(), m = p.at("m").get<int>();
  check_particle_memory(n, n, "/n");
  if (n < 8 * m) throw ConfigError("/n", "need at least 8 particles per cell and side (n >= 8 m)");
  const bool forced = p.at("forced").get<bool>(), taylor_green = p.at("initial") == "taylor_green";
  if (!forced && !taylor_green)
    throw ConfigError("/initial", "an unforced box at rest stays at rest: set initial = taylor_green or forced = true");
  const double l = p.at("l").get<double>();
  s->nx = s->ny = n;
  s->dx = l / n;
  s->box = PeriodicBox{l, l, true, true};
  s->eta = p.at("eta_over_l").get<double>() * l;
  s->rho0 = p.at("rho").get<double>();
  s->phase_viscosity = {p.at("mu").get<double>()};
  read_sph_discretization(*s, p, "");
  const double support = s->smoothing_kernel().support();
  if (l < 3.0 * (support + 0.5 * s->dx))
    throw ConfigError("/n", "the periodic box must hold 3 SPH supports plus the list skin; raise n");
  if (s->eta * 6.0 > l) throw ConfigError("/eta_over_l", "eta' too large for the domain: need 6 eta' <= L");
  const double nu = s->phase_viscosity[0] / s->rho0, k = 2.0 * M_PI * m / l;
  const double amplitude = p.at("re").get<double>() * k * nu, g = forced ? 2.0 * k * k * nu * amplitude : 0.0;
  s->cellular_mode = Scene::CellularMode{k, forced ? amplitude : 0.0, taylor_green ? amplitude : 0.0, 2.0 * k * k * nu};
  if (forced) s->body_force = [g, k](double x, double y) { return Vec2(g * cellular_mode(x, y, k)); };
  else s->body_force = [](double, double) { return Vec2(0.0, 0.0); };
  if (taylor_green) s->initial_velocity = [amplitude, k](double x, double y) { return Vec2(amplitude * cellular_mode(x, y, k)); };
  s->x_invariant = false;
  s->analytic_peak = amplitude;
  s->sound_speed = p.at("sound_speed_factor").get<double>() * amplitude;
  s->background_pressure = p.at("background_pressure_factor").get<double>() * s->rho0 * s->sound_speed * s->sound_speed;
  return s;
}

}  // namespace

void register_cellular_scene(Registry& r) {
  r.scenes.add({"cellular",
                "doubly periodic m x m cells, force g (sin kx cos ky, -cos kx sin ky) and/or a Taylor-Green start; "
                "exact velocity A(t) times that mode (not x-invariant)",
                cellular_schema()},
               make_cellular);
}

}  // namespace closurelab
