// The cylinder-lattice scene (flow through a porous medium): a periodic square cell of side L, periodic in x and y, one cylinder of
// radius a at its centre, the square lattice of spacing ε' = L/n over the whole cell; the lattice particles inside
// the cylinder (distance to the centre below a) are frozen at zero velocity (5.3), the others are fluid driven by
// the body force g along x. Stokes flow at small g (Re = a⟨u⟩/ν ≪ 1). The reference is the Darcy permeability
// k = μ⟨u⟩/(ρ g) of the square array from our boundary-collocation Stokes solve (which reproduces Sangani &
// Acrivos's 1982 table; core/scenes/square_array_stokes.hpp).
#include "core/scenes/cylinder_lattice_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/registry.hpp"
#include "core/scenes/square_array_stokes.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

// Harmonics of the collocation solve: converged to ~1e-7 of the drag for a/L <= 0.4 (tests/unit/
// test_square_array_stokes.cpp), its boundary residual is reported with the reference.
constexpr int kReferenceModes = 32;

ParamSchema cylinder_lattice_schema() {
  ParamSchema schema{
      integer_param("n", 48, "particles per side of the cell (epsilon' = L / n)", 8, 4096),
      number_param("l", 1.0, "cell side L", 0.0, {}, true),
      number_param("radius_over_length", 0.2, "cylinder radius a / L (solid fraction c = pi a^2 / L^2); a < L/2", 0.0,
                   {}, true),
      number_param("rho", 1.0, "fluid density", 0.0, {}, true),
      number_param("mu", 1.0, "dynamic viscosity", 0.0, {}, true),
      number_param("g", 0.01, "body force per unit mass along x, on the fluid only (Re = a <u> / nu ~ 1e-4 at 0.01)",
                   0.0, {}, true),
      number_param("eta_over_l", 1.0 / 16.0, "averaging scale eta'/L", 0.0, 0.5, true),
      number_param("background_pressure_factor", 0.002,
                   "background pressure / (rho c^2); small: its lattice error grows k without bound at 1.0", 0.0, 10.0),
      number_param("sound_speed_factor", 10.0,
                   "sound speed / V, V^2 = max(U^2, nu U / L, g L, nu^2 / L^2) (Morris et al. 1997, and nu / L for an "
                   "underdamped cell; U the reference's gap-velocity estimate): the density varies by about 1/factor^2",
                   1.0, {}),
  };
  for (const ParamSpec& p : sph_discretization_params())
    if (p.name != "sound_speed_factor") schema.push_back(p);
  // The solid's boundary model: zero_velocity (5.3), or Morris et al.'s (1997) ghost velocities with distances to
  // the cylinder's nominal surface (rows stored before it: zero_velocity, upgraded_scene_params).
  for (const ParamSpec& p : wall_model_params()) schema.push_back(p);
  return schema;
}

std::unique_ptr<Scene> make_cylinder_lattice(const json& p) {
  auto s = std::make_unique<Scene>();
  s->name = "cylinder-lattice";
  s->params = p;
  const int n = p.at("n").get<int>();
  check_particle_memory(n, n, "/n");
  const double l = p.at("l").get<double>(), a_over_l = p.at("radius_over_length").get<double>();
  if (a_over_l >= 0.5)
    throw ConfigError("/radius_over_length",
                      "the cylinder does not fit the cell: need a < L/2 (got a/L = " + std::to_string(a_over_l) + ")");
  const double a = a_over_l * l;
  s->nx = s->ny = n;
  s->dx = l / n;
  s->box = PeriodicBox{l, l, true, true};
  s->eta = p.at("eta_over_l").get<double>() * l;
  s->rho0 = p.at("rho").get<double>();
  s->phase_viscosity = {p.at("mu").get<double>()};
  read_sph_discretization(*s, p, "");
  const double support = s->smoothing_kernel().support();
  if (l < 3.0 * (support + 0.5 * s->dx))
    throw ConfigError("/n", "the periodic cell must hold 3 SPH supports plus the list skin; raise n");
  if (s->eta * 6.0 > l) throw ConfigError("/eta_over_l", "eta' too large for the cell: need 6 eta' <= L");
  // Resolution: the gap between neighbouring cylinders (L − 2a) must hold two SPH supports, so that no fluid
  // particle is within reach of two cylinders at once and the gap has interior fluid; and the cylinder's
  // diameter one support, so that no fluid particle reaches the fluid on the far side through the solid.
  const double gap = l - 2.0 * a;
  if (gap < 2.0 * support) {
    std::ostringstream msg;
    msg << "too few particles across the gap between cylinders: L - 2a = " << gap / s->dx
        << " spacings, need 2 SPH supports (" << 2.0 * support / s->dx << "); raise n or lower radius_over_length";
    throw ConfigError("/n", msg.str());
  }
  if (2.0 * a < support) {
    std::ostringstream msg;
    msg << "the cylinder is thinner than the SPH support: 2a = " << 2.0 * a / s->dx << " spacings, need "
        << support / s->dx << "; raise n or radius_over_length";
    throw ConfigError("/n", msg.str());
  }
  const double cx = 0.5 * l, cy = 0.5 * l, a2 = a * a;
  s->solid_at = [cx, cy, a2](double x, double y) { return (x - cx) * (x - cx) + (y - cy) * (y - cy) < a2; };
  s->wall_model = parse_name<WallModel>(p.at("wall_model").get<std::string>(), "/wall_model");
  s->ghost_beta_max = p.at("ghost_beta_max").get<double>();
  if (s->wall_model == WallModel::ghost_velocity)
    s->solid_depth = [cx, cy, a](double x, double y) { return a - std::hypot(x - cx, y - cy); };
  const double g = p.at("g").get<double>(), rho = s->rho0, mu = s->phase_viscosity[0], nu = mu / rho;
  s->force_x = [g](double) { return g; };
  s->body_force = [g](double, double) { return Vec2(g, 0.0); };

  const SquareArrayStokesResult ref = square_array_stokes(a_over_l, kReferenceModes);
  const double c = M_PI * a_over_l * a_over_l;
  Scene::Permeability perm;
  perm.reference = ref.permeability * l * l;
  perm.body_force = g;
  perm.solid_fraction = c;
  std::ostringstream src;
  src << "boundary-collocation Stokes solve of the square array (" << kReferenceModes
      << " odd harmonics, boundary residual " << ref.boundary_residual
      << " of the flux; reproduces Sangani & Acrivos 1982); F/(mu U) = " << ref.drag;
  perm.reference_source = src.str();
  perm.solid_size = a;
  // The radius whose reference permeability is k (k falls monotonically with a): bisection on a/L in (0, 1/2).
  perm.solid_size_for = [l](double k) {
    double lo = 1e-3, hi = 0.499;
    const double target = k / (l * l);
    if (!(target < square_array_stokes(lo, kReferenceModes).permeability) ||
        !(target > square_array_stokes(hi, 48).permeability))
      return std::nan("");
    for (int it = 0; it < 50 && hi - lo > 1e-12; ++it) {
      const double mid = 0.5 * (lo + hi);
      (square_array_stokes(mid, mid > 0.45 ? 48 : kReferenceModes).permeability > target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi) * l;
  };
  s->permeability = perm;

  // Sound speed (Morris, Fox & Zhu 1997): c^2 = max(U^2, nu U / L, g L) / delta with delta the tolerated
  // relative density variation; here c = sound_speed_factor * V, so delta ~ 1 / factor^2. In Stokes flow the
  // body-force term g L dominates: the pressure balances the force over the cell. U: the reference superficial
  // velocity through the narrowest section (L − 2a), times 1.5 for a parabolic gap profile. Besides, V >= nu / L:
  // a compression of the cell relaxes at the rate c^2 / nu when c L / nu is small (overdamped sound), which at
  // small g (c ~ sqrt(g L) < nu / L) is slower than the flow's own relaxation (nu / k) and delays the steady state
  // by orders of magnitude (measured: n = 48, g = 0.01, c = 1: not steady by t = 2 = 60 k/nu). With c L / nu >= 10
  // the cell's sound is underdamped and decays at the viscous rate; in the time step (5.21)-(5.22) the viscous
  // limit rho eps'^2 / mu stays the smaller one for n > 10, so this costs nothing.
  const double u_mean = perm.superficial_velocity(rho, mu);
  const double u_gap = 1.5 * u_mean * l / gap;
  s->sound_speed = solid_scene_sound_speed(p.at("sound_speed_factor").get<double>(), u_gap, nu, g, l);
  s->background_pressure = p.at("background_pressure_factor").get<double>() * s->rho0 * s->sound_speed * s->sound_speed;
  s->analytic_peak = u_gap;  // no analytic field: the gap-velocity estimate sets the scales (sound speed, progress)
  s->x_invariant = false;
  return s;
}

}  // namespace

double solid_scene_sound_speed(double factor, double u, double nu, double g, double l) {
  return factor * std::sqrt(std::max({u * u, nu * u / l, g * l, nu * nu / (l * l)}));
}

void register_cylinder_lattice_scene(Registry& r) {
  r.scenes.add({"cylinder-lattice",
                "periodic square lattice of cylinders (porous medium), radius a = radius_over_length L, body force "
                "g along x on the fluid, frozen solid particles; reference: the Darcy permeability of the square "
                "array (not x-invariant)",
                cylinder_lattice_schema()},
               make_cylinder_lattice);
}

}  // namespace closurelab
