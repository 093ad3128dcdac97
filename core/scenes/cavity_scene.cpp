// The lid-driven cavity (DESIGN.md §5, "lid-driven-cavity"), as PySPH 1.0b1's pysph/examples/cavity.py sets it up:
// a square of side L filled with n × n fluid particles on the lattice (i + ½) L/n, inside solid walls of particles
// on the same lattice continued outwards; the solid particles above the square (the lid, corners included) move
// along x at the lid speed U, the others rest. Mass ρ0 ε'² (PySPH's m = ρ0 dx², `particle_mass` cell_volume),
// ν = U L / Re, sound speed c = 10 U, no body force, the equation of state p = c² (ρ − ρ0). The walls are as many
// layers as the SPH support holds spacings, plus one (PySPH lays 5: the layers beyond the support of every fluid
// particle add nothing); the box is the square with its walls, periodic in neither direction, so the fluid fills
// [w, w + L]², w the walls' thickness (PySPH's fluid fills [0, L]²: the same particles shifted by w). The flow is
// meant for the transport-velocity formulation with the generalized wall condition
// (core/sph/transport_velocity.hpp), which PySPH runs on it; the standard formulation is refused.
#include "core/scenes/cavity_scene.hpp"

#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

ParamSchema cavity_schema() {
  ParamSchema schema{
      integer_param("n", 50, "fluid particles per side of the cavity (epsilon' = L / n; PySPH's --nx)", 8, 4096),
      number_param("re", 100.0, "Reynolds number U L / nu (PySPH's --re)", 0.0, {}, true),
      number_param("u", 1.0, "lid speed U", 0.0, {}, true),
      number_param("l", 1.0, "cavity side L (the fluid's square; the walls lie outside it)", 0.0, {}, true),
      number_param("rho", 1.0, "fluid density rho0", 0.0, {}, true),
      number_param("eta_over_l", 1.0 / 16.0, "averaging scale eta'/L", 0.0, 0.5, true)};
  const ParamSchema sph = sph_discretization_params();
  schema.insert(schema.end(), sph.begin(), sph.end());
  return schema;
}

std::unique_ptr<Scene> make_cavity(const json& p) {
  auto s = std::make_unique<Scene>();
  s->name = "lid-driven-cavity";
  s->params = p;
  const int n = p.at("n").get<int>();
  const double l = p.at("l").get<double>(), u = p.at("u").get<double>(), re = p.at("re").get<double>();
  s->dx = l / n;
  read_sph_discretization(*s, p, "");
  const int layers = static_cast<int>(std::ceil(s->smoothing_kernel().support() / s->dx - 1e-9)) + 1;
  const double w = layers * s->dx;
  s->nx = s->ny = n + 2 * layers;
  check_particle_memory(s->nx, s->ny, "/n");
  s->box = PeriodicBox{l + 2.0 * w, l + 2.0 * w, false, false};
  s->eta = p.at("eta_over_l").get<double>() * l;
  if (s->eta * 6.0 > l) throw ConfigError("/eta_over_l", "eta' too large for the cavity: need 6 eta' <= L");
  s->rho0 = p.at("rho").get<double>();
  const double nu = u * l / re;  // PySPH: nu = Umax L / re
  s->phase_viscosity = {s->rho0 * nu};
  s->mass_from_cell_volume = true;
  const double lo = w, hi = w + l;
  s->solid_at = [lo, hi](double x, double y) { return x < lo || x > hi || y < lo || y > hi; };
  s->solid_velocity = [hi, u](double, double y) { return y > hi ? Vec2(u, 0.0) : Vec2(0.0, 0.0); };
  s->needs_transport_velocity = true;
  s->cavity = Scene::LidDrivenCavity{l, w, u, re};
  s->body_force = [](double, double) { return Vec2(0.0, 0.0); };
  s->x_invariant = false;
  s->analytic_peak = u;
  s->sound_speed = p.at("sound_speed_factor").get<double>() * u;  // PySPH: c0 = 10 Umax
  return s;
}

}  // namespace

void register_cavity_scene(Registry& r) {
  r.scenes.add({"lid-driven-cavity",
                "lid-driven cavity (PySPH's cavity.py): fluid in a square of side L inside walls, the top one sliding "
                "at U; Re = U L / nu; reference: Ghia, Ghia & Shin (1982)'s centre-line profiles; for the "
                "transport-velocity formulation",
                cavity_schema()},
               make_cavity);
}

}  // namespace closurelab
