// The Taylor–Green vortex (DESIGN.md §5, "taylor-green"), as PySPH 1.0b1's pysph/examples/taylor_green.py sets it
// up: a doubly periodic square box of side L, n × n particles on the lattice (i + ½, j + ½) L/n, mass ρ L²/n²
// (`particle_mass` cell_volume, PySPH's m = ρ0 dx²), the velocity of the exact solution at t = 0,
//   u = −U cos kx sin ky,  v = U sin kx cos ky,  k = 2π/L,
// ν = U L / Re, sound speed c = 10 U, no body force, and the equation of state p = c² (ρ − ρ0) without a
// background term (PySPH's StateEquation with b = 1; `background_pressure_factor` adds one, which the standard
// formulation needs against the tensile instability). The exact solution decays as e^{bt}, b = −2k²ν = −8π²/Re at
// L = U = 1 (Scene::taylor_green, with its pressure). PySPH also sets the particles' initial pressure from the
// exact solution, but its transport-velocity scheme recomputes p from the summation density before the first use,
// so that pressure never acts; here too the pressure is the summation density's from the first evaluation, and
// the exact one is the scene's for comparisons. The flow is meant for the transport-velocity formulation
// (solver.formulation transport_velocity; core/sph/transport_velocity.hpp), which PySPH runs on it by default.
#include "core/scenes/taylor_green_scene.hpp"

#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

ParamSchema taylor_green_schema() {
  ParamSchema schema{
      integer_param("n", 50, "particles per side (epsilon' = L / n; PySPH's --nx)", 16, 4096),
      number_param("re", 100.0, "Reynolds number U L / nu (PySPH's --re)", 0.0, {}, true),
      number_param("u", 1.0, "velocity scale U: the largest |v| at t = 0", 0.0, {}, true),
      number_param("l", 1.0, "box side L", 0.0, {}, true),
      number_param("rho", 1.0, "fluid density rho0", 0.0, {}, true),
      number_param("eta_over_l", 1.0 / 16.0, "averaging scale eta'/L", 0.0, 0.5, true),
      number_param("background_pressure_factor", 0.0,
                   "background pressure of the equation of state / (rho c^2) (0: PySPH's p = c^2 (rho - rho0); the "
                   "transport velocity's own p_b is the solver's)",
                   0.0, 10.0),
      string_param("particle_mass", "cell_volume",
                   "cell_volume: m = rho0 L^2/n^2 (PySPH); lattice: m = rho0/n0, the lattice's summation density rho0",
                   {"cell_volume", "lattice"}),
      number_param("perturbation", 0.0,
                   "random shift of each particle off the lattice, a fraction of epsilon' (PySPH's --perturb: U[0, 1) "
                   "draws of numpy.random.seed(1)); 0: the lattice",
                   0.0, 0.5)};
  const ParamSchema sph = sph_discretization_params();
  schema.insert(schema.end(), sph.begin(), sph.end());
  return schema;
}

std::unique_ptr<Scene> make_taylor_green(const json& p) {
  auto s = std::make_unique<Scene>();
  s->name = "taylor-green";
  s->params = p;
  const int n = p.at("n").get<int>();
  check_particle_memory(n, n, "/n");
  const double l = p.at("l").get<double>(), u = p.at("u").get<double>(), re = p.at("re").get<double>();
  s->nx = s->ny = n;
  s->dx = l / n;
  s->box = PeriodicBox{l, l, true, true};
  s->eta = p.at("eta_over_l").get<double>() * l;
  s->rho0 = p.at("rho").get<double>();
  const double nu = u * l / re;  // PySPH: nu = U L / re
  s->phase_viscosity = {s->rho0 * nu};
  s->mass_from_cell_volume = p.at("particle_mass") == "cell_volume";
  read_sph_discretization(*s, p, "");
  const double support = s->smoothing_kernel().support();
  if (l < 3.0 * (support + 0.5 * s->dx))
    throw ConfigError("/n", "the periodic box must hold 3 SPH supports plus the list skin; raise n");
  if (s->eta * 6.0 > l) throw ConfigError("/eta_over_l", "eta' too large for the domain: need 6 eta' <= L");
  const double k = 2.0 * M_PI / l;
  s->taylor_green = Scene::TaylorGreenVortex{k, u, 2.0 * k * k * nu, s->rho0};
  const Scene::TaylorGreenVortex tg = *s->taylor_green;
  s->initial_velocity = [tg](double x, double y) { return tg.velocity_at(x, y, 0.0); };
  // The same vortex as a cellular mode (−cos kx sin ky, sin kx cos ky) = cellular_mode(x + L/4, y + L/4), so that
  // the 2D reduced model (mesh_2d) runs on it.
  s->cellular_mode = Scene::CellularMode{k, 0.0, u, 2.0 * k * k * nu, 0.25 * l};
  s->position_perturbation = p.at("perturbation").get<double>();
  s->body_force = [](double, double) { return Vec2(0.0, 0.0); };
  s->x_invariant = false;
  s->analytic_peak = u;
  s->sound_speed = p.at("sound_speed_factor").get<double>() * u;  // PySPH: c0 = 10 U
  s->background_pressure = p.at("background_pressure_factor").get<double>() * s->rho0 * s->sound_speed * s->sound_speed;
  return s;
}

}  // namespace

void register_taylor_green_scene(Registry& r) {
  r.scenes.add({"taylor-green",
                "Taylor-Green vortex in a doubly periodic box (PySPH's taylor_green.py), Re = U L / nu; exact velocity "
                "decaying as exp(-8 pi^2 t / Re) (L = U = 1); for the transport-velocity formulation",
                taylor_green_schema()},
               make_taylor_green);
}

}  // namespace closurelab
