// The cylinder-channel scene (a walled scene that is not x-invariant): a square box of side L, periodic in
// x, walls 3η' thick at the bottom and the top (5.3), one cylinder of radius a at the centre of the box, the square
// lattice of spacing ε' = L/n over the whole box; the lattice particles in the walls and inside the cylinder are frozen
// at zero velocity, the others are fluid driven by the body force g along x (a row of obstacles in a channel, Stokes
// flow at small g). No analytic solution: the direct SPH of the same box is the reference.
#include "core/scenes/cylinder_channel_scene.hpp"
#include "core/scenes/cylinder_lattice_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/scenes/wall_rows.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

ParamSchema cylinder_channel_schema() {
  ParamSchema schema{
      integer_param("n", 48, "particles per side of the box (epsilon' = L / n)", 8, 4096),
      number_param("l", 1.0, "box side L (the period in x and the height, walls included)", 0.0, {}, true),
      number_param("radius_over_length", 0.15, "cylinder radius a / L, the cylinder at the box's centre", 0.0, {}, true),
      number_param("eta_over_l", 1.0 / 16.0, "averaging scale eta'/L; the walls are 3 eta' thick", 0.0, 0.5, true),
      number_param("rho", 1.0, "fluid density", 0.0, {}, true),
      number_param("mu", 1.0, "dynamic viscosity", 0.0, {}, true),
      number_param("g", 0.01, "body force per unit mass along x, on the fluid only", 0.0, {}, true),
      number_param("background_pressure_factor", 0.002, "background pressure / (rho c^2)", 0.0, 10.0),
      number_param("sound_speed_factor", 10.0,
                   "sound speed / V, V^2 = max(U^2, nu U / L, g L, nu^2 / L^2), U the peak of the channel without the "
                   "cylinder (as cylinder-lattice's rule)",
                   1.0, {}),
  };
  for (const ParamSpec& p : sph_discretization_params())
    if (p.name != "sound_speed_factor") schema.push_back(p);
  return schema;
}

std::unique_ptr<Scene> make_cylinder_channel(const json& p) {
  auto s = std::make_unique<Scene>();
  s->name = "cylinder-channel";
  s->params = p;
  const int n = p.at("n").get<int>();
  check_particle_memory(n, n, "/n");
  const double l = p.at("l").get<double>(), a = p.at("radius_over_length").get<double>() * l;
  s->nx = s->ny = n;
  s->dx = l / n;
  s->box = PeriodicBox{l, l, true, false};
  s->eta = p.at("eta_over_l").get<double>() * l;
  s->has_walls = true;
  s->wall_lo = 3.0 * s->eta;
  s->wall_hi = l - 3.0 * s->eta;
  check_rows_off_wall_surfaces(*s, l, "/eta_over_l", "n");
  s->rho0 = p.at("rho").get<double>();
  s->phase_viscosity = {p.at("mu").get<double>()};
  read_sph_discretization(*s, p, "");
  const double support = s->smoothing_kernel().support();
  if (l < 3.0 * (support + 0.5 * s->dx))
    throw ConfigError("/n", "the periodic length must hold 3 SPH supports plus the list skin; raise n");
  if (s->wall_lo < support)
    throw ConfigError("/eta_over_l", "walls (3 eta') thinner than the SPH support; raise eta' or n");
  // The gap between the cylinder and each wall must hold two SPH supports (no fluid particle within reach of both),
  // and the cylinder's diameter one support (no fluid particle reaching the far side through the solid).
  const double gap = 0.5 * (s->wall_hi - s->wall_lo) - a;
  if (!(gap >= 2.0 * support)) {
    std::ostringstream msg;
    msg << "the cylinder does not leave two SPH supports to each wall: the gap is " << gap / s->dx
        << " spacings, need " << 2.0 * support / s->dx << "; lower radius_over_length or eta_over_l, or raise n";
    throw ConfigError("/radius_over_length", msg.str());
  }
  if (2.0 * a < support)
    throw ConfigError("/n", "the cylinder is thinner than the SPH support; raise n or radius_over_length");
  const double cx = 0.5 * l, cy = 0.5 * l, a2 = a * a;
  s->solid_at = [cx, cy, a2](double x, double y) { return (x - cx) * (x - cx) + (y - cy) * (y - cy) < a2; };
  const double g = p.at("g").get<double>(), mu = s->phase_viscosity[0], nu = mu / s->rho0;
  s->force_x = [g](double) { return g; };
  s->body_force = [g](double, double) { return Vec2(g, 0.0); };
  // Scales (sound speed, progress, divergence guards): the peak of the channel without the cylinder, g w² / (8 ν).
  const double w = s->wall_hi - s->wall_lo, u = g * w * w / (8.0 * nu);
  s->sound_speed = solid_scene_sound_speed(p.at("sound_speed_factor").get<double>(), u, nu, g, l);
  s->background_pressure = p.at("background_pressure_factor").get<double>() * s->rho0 * s->sound_speed * s->sound_speed;
  s->analytic_peak = u;
  s->x_invariant = false;
  return s;
}

}  // namespace

void register_cylinder_channel_scene(Registry& r) {
  r.scenes.add({"cylinder-channel",
                "a row of cylinders in a channel: periodic in x, walls 3 eta' thick in y, one cylinder of radius a at "
                "the box's centre, body force g along x on the fluid, frozen solid particles; reference: the direct "
                "SPH (not x-invariant)",
                cylinder_channel_schema()},
               make_cylinder_channel);
}

}  // namespace closurelab
