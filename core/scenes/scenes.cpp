// The canonical scenes of DESIGN.md §5, registered in the "scene" family.
#include <cmath>

#include "core/scenes/analytic.hpp"
#include "core/scenes/cellular_scene.hpp"
#include "core/scenes/cylinder_channel_scene.hpp"
#include "core/scenes/cylinder_lattice_scene.hpp"
#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/numpy_uniform.hpp"
#include "core/scenes/layered_scene.hpp"
#include "core/scenes/cavity_scene.hpp"
#include "core/scenes/taylor_green_scene.hpp"
#include "core/scenes/wall_rows.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

ParticleSystem Scene::make_particles() const {
  ParticleSystem ps;
  const double m = particle_mass();
  for (int j = 0; j < ny; ++j) {
    const double y = (j + 0.5) * dx;
    const int ph = phase(y);
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5) * dx;
      ps.add(x, y, m, ph, is_solid(x, y));
    }
  }
  if (position_perturbation > 0.0) {
    NumpyLegacyUniform uniform(1);
    const double shift = position_perturbation * dx;
    for (std::size_t a = 0; a < ps.size(); ++a) ps.x[a] += uniform.next() * shift;
    for (std::size_t a = 0; a < ps.size(); ++a) ps.y[a] += uniform.next() * shift;
  }
  if (initial_velocity || solid_velocity)
    for (std::size_t a = 0; a < ps.size(); ++a) {
      const auto& velocity = ps.fixed[a] ? solid_velocity : initial_velocity;
      if (!velocity) continue;
      const Vec2 v = velocity(ps.x[a], ps.y[a]);
      ps.vx[a] = v.x();
      ps.vy[a] = v.y();
    }
  return ps;
}

Scene Scene::narrowest_strip() const {
  if (!x_invariant || !box.periodic_x) return *this;
  const double support = smoothing_kernel().support();
  const int columns = static_cast<int>(std::ceil(3.0 * (support + 0.5 * dx) / dx - 1e-9));
  if (columns >= nx) return *this;
  Scene s = *this;
  s.nx = columns;
  s.box.lx = columns * dx;
  return s;
}

double Scene::particle_mass() const {
  if (mass_from_cell_volume) return rho0 * dx * dx;
  // m = rho0 / n0 with n0 the number density of the perfect lattice, so the SPH density at rest is rho0.
  const SmoothingKernel w = smoothing_kernel();
  const int reach = static_cast<int>(std::ceil(w.support() / dx)) + 1;
  double n0 = 0.0;
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b) n0 += w.w(dx * std::hypot(a, b));
  return rho0 / n0;
}

bool Scene::in_fluid(double y) const {
  const double tol = 1e-12 * box.ly;
  return !has_walls || (y > wall_lo + tol && y < wall_hi - tol);
}

bool Scene::in_interior(double y) const {
  const double tol = 1e-12 * box.ly;
  return !has_walls || (y >= wall_lo + 3.0 * eta - tol && y <= wall_hi - 3.0 * eta + tol);
}

double Scene::max_viscosity() const {
  double m = 0.0;
  for (double v : phase_viscosity) m = std::max(m, v);
  return m;
}

double Scene::time_scale() const {
  if (cellular_mode && cellular_mode->decay_rate > 0.0) return 1.0 / cellular_mode->decay_rate;
  if (cavity) return cavity->side / cavity->lid_speed;  // L / U (the box, walls included, is larger)
  const double length = has_walls ? wall_hi - wall_lo : box.ly;
  return analytic_peak > 0.0 ? length / analytic_peak : 0.0;
}

double Scene::viscosity_at(const Vec2& point) const { return phase_viscosity.at(phase(point.y())); }

ParamSchema wall_model_params() {
  return {
      string_param("wall_model", "zero_velocity",
                   "zero_velocity: wall particles at rest (5.3, paper); ghost_velocity: Morris ghost velocities",
                   names_of<WallModel>()),
      number_param("ghost_beta_max", 1.0e6, "cap on 1 + d_wall/d_fluid in the ghost-velocity wall (Morris: 1.5)", 1.0, {}),
  };
}

json upgraded_scene_params(json scene) {
  // The channels' and kolmogorov's averaging width was stored as eta_over_ly before every scene named it eta_over_l.
  if (scene.is_object() && scene.contains("eta_over_ly") && !scene.contains("eta_over_l")) {
    scene["eta_over_l"] = scene["eta_over_ly"];
    scene.erase("eta_over_ly");
  }
  if (scene.is_object() && scene.value("name", "") == "cylinder-lattice" && !scene.contains("wall_model"))
    for (const ParamSpec& p : wall_model_params()) scene[p.name] = p.default_value;
  return scene;
}

void read_sph_discretization(Scene& s, const json& p, const std::string& path) {
  s.smoothing_type = parse_name<SmoothingKernel::Type>(p.at("smoothing_kernel").get<std::string>(), path + "/smoothing_kernel");
  s.h = p.at("h_over_dx").get<double>() * s.dx;
}

void check_strip_width(const Scene& s, const std::string& path) {
  const double support = s.smoothing_kernel().support();
  if (s.box.periodic_x && s.box.lx < 3.0 * (support + 0.5 * s.dx))
    throw ConfigError(path + "/n_x", "the periodic strip (n_x epsilon') must hold 3 SPH supports plus the list skin; "
                                     "raise n_x to at least " +
                                         std::to_string(static_cast<int>(std::ceil(3.0 * (support + 0.5 * s.dx) / s.dx))));
}

ParamSchema sph_discretization_params() {
  return {
      string_param("smoothing_kernel", "quintic", "SPH smoothing function", names_of<SmoothingKernel::Type>()),
      number_param("h_over_dx", 1.0, "SPH smoothing length h / epsilon'", 0.5, 3.0),
      number_param("sound_speed_factor", 10.0, "sound speed / analytic peak velocity (>= 10)", 10.0, {}),
  };
}

namespace {

ParamSchema channel_schema() {
  ParamSchema schema{
      integer_param("n_y", 48, "particle rows across L_y (epsilon' = L_y / n_y)", 8, 4096),
      integer_param("n_x", 12, "particle columns of the periodic strip (x-extent = n_x epsilon')", 4, 100000),
      number_param("eta_over_l", 1.0 / 16.0,
                   "averaging scale eta'/L_y (L = L_y; eta_over_ly, its earlier name, still read); walls are 3 eta' "
                   "thick (5.3)",
                   0.0, 0.5, true),
      number_param("ly", 1.0, "domain height L_y", 0.0, {}, true),
      number_param("rho", 1.0, "fluid density", 0.0, {}, true),
      number_param("mu", 1.0, "dynamic viscosity", 0.0, {}, true),
      number_param("g", 1.0, "body force per unit mass along x", {}, {}),
      number_param("background_pressure_factor", 1.0, "background pressure / (rho c^2)", 0.0, 10.0),
  };
  for (const ParamSchema& more : {wall_model_params(), sph_discretization_params()})
    schema.insert(schema.end(), more.begin(), more.end());
  return schema;
}

ParamSchema kolmogorov_schema() {
  ParamSchema schema{
      integer_param("n_y", 48, "particle rows across L_y (epsilon' = L_y / n_y)", 8, 4096),
      integer_param("n_x", 12, "particle columns of the periodic strip", 4, 100000),
      number_param("eta_over_l", 1.0 / 16.0, "averaging scale eta'/L_y (L = L_y; eta_over_ly, its earlier name, still read)",
                   0.0, 0.5, true),
      number_param("ly", 1.0, "domain height L_y", 0.0, {}, true),
      number_param("rho", 1.0, "fluid density", 0.0, {}, true),
      number_param("mu", 1.0, "dynamic viscosity", 0.0, {}, true),
      number_param("g", 1.0, "force amplitude per unit mass", 0.0, {}, true),
      integer_param("k", 1, "wavenumber of the force (periods across L_y)", 1, 64),
      number_param("background_pressure_factor", 1.0, "background pressure / (rho c^2)", 0.0, 10.0)};
  const ParamSchema sph = sph_discretization_params();
  schema.insert(schema.end(), sph.begin(), sph.end());
  return schema;
}

// Builds the common channel geometry from resolved parameters; `path` is the scene's JSON path.
Scene make_channel(const std::string& name, const json& p, const std::string& path) {
  Scene s;
  s.name = name;
  s.params = p;
  s.ny = p.at("n_y").get<int>();
  s.nx = p.at("n_x").get<int>();
  check_particle_memory(s.nx, s.ny, "/n_x");
  const double ly = p.at("ly").get<double>();
  s.dx = ly / s.ny;
  s.box = PeriodicBox{s.nx * s.dx, ly, true, false};
  s.eta = p.at("eta_over_l").get<double>() * ly;
  s.has_walls = true;
  s.wall_lo = 3.0 * s.eta;
  s.wall_hi = ly - 3.0 * s.eta;
  check_rows_off_wall_surfaces(s, ly, path + "/eta_over_l", "n_y");
  int fluid_rows = 0;
  for (int j = 0; j < s.ny; ++j) fluid_rows += !s.is_wall((j + 0.5) * s.dx);
  if (s.wall_hi - s.wall_lo < 4.0 * s.dx || fluid_rows < 4)
    throw ConfigError(path + "/eta_over_l", "eta' too large for the domain: the walls (3 eta' each) leave " +
                                                 std::to_string(fluid_rows) + " fluid rows (need >= 4; need eta'/L_y < 1/6)");
  s.wall_model = parse_name<WallModel>(p.at("wall_model").get<std::string>(), path + "/wall_model");
  s.ghost_beta_max = p.at("ghost_beta_max").get<double>();
  s.rho0 = p.at("rho").get<double>();
  s.phase_viscosity = {p.at("mu").get<double>()};
  read_sph_discretization(s, p, path);
  check_strip_width(s, path);
  if (s.wall_lo < s.smoothing_kernel().support())
    throw ConfigError(path + "/eta_over_l", "walls (3 eta') thinner than the SPH support; raise eta' or n_y");
  s.x_invariant = true;
  return s;
}

void finish_sound_speed(Scene& s) {
  double peak = 0.0;
  const double lo = s.has_walls ? s.wall_lo : 0.0, hi = s.has_walls ? s.wall_hi : s.box.ly;
  for (int k = 0; k <= 2000; ++k) {
    const double y = lo + (hi - lo) * k / 2000.0;
    peak = std::max(peak, std::abs(s.analytic_vx(y)));
  }
  s.analytic_peak = peak;
  s.sound_speed = s.params.at("sound_speed_factor").get<double>() * std::max(peak, 1e-300);
  s.background_pressure = s.params.at("background_pressure_factor").get<double>() * s.rho0 * s.sound_speed * s.sound_speed;
}

}  // namespace

void register_scenes(Registry& r) {
  register_layered_scene(r);
  register_cellular_scene(r);
  register_cylinder_lattice_scene(r);
  register_cylinder_channel_scene(r);
  register_taylor_green_scene(r);
  register_cavity_scene(r);
  r.scenes.add({"poiseuille-uniform", "Poiseuille flow between walls at 3 eta' and L_y - 3 eta', uniform force (par. 5)",
                channel_schema()},
               [](const json& p) {
                 auto s = std::make_unique<Scene>(make_channel("poiseuille-uniform", p, ""));
                 const double l1 = s->wall_lo, l2 = s->wall_hi, rho = s->rho0, g = p.at("g").get<double>(),
                              mu = s->phase_viscosity[0];
                 s->force_x = [g](double) { return g; };
                 s->uniform_force_x = g;
                 s->analytic_vx = [=](double y) { return poiseuille_velocity(y, l1, l2, rho, g, mu); };
                 finish_sound_speed(*s);
                 return s;
               });
  r.scenes.add(
      {"kolmogorov",
       "periodic in x and y, no walls, force g sin(2 pi k y / L_y): a closure's error is its own (DESIGN.md par. 5)",
       kolmogorov_schema()},
      [](const json& p) {
        auto s = std::make_unique<Scene>();
        s->name = "kolmogorov";
        s->params = p;
        s->ny = p.at("n_y").get<int>();
        s->nx = p.at("n_x").get<int>();
        check_particle_memory(s->nx, s->ny, "/n_x");
        const double ly = p.at("ly").get<double>();
        s->dx = ly / s->ny;
        s->box = PeriodicBox{s->nx * s->dx, ly, true, true};
        s->eta = p.at("eta_over_l").get<double>() * ly;
        s->rho0 = p.at("rho").get<double>();
        s->phase_viscosity = {p.at("mu").get<double>()};
        read_sph_discretization(*s, p, "");
        check_strip_width(*s, "");
        const double support = s->smoothing_kernel().support();
        if (ly < 3.0 * (support + 0.5 * s->dx))
          throw ConfigError("/n_y", "the periodic height must hold 3 SPH supports plus the list skin; raise n_y");
        if (s->eta * 6.0 > ly) throw ConfigError("/eta_over_l", "eta' too large for the domain: need 6 eta' <= L_y");
        const double g = p.at("g").get<double>(), nu = s->phase_viscosity[0] / s->rho0;
        const double kw = 2.0 * M_PI * p.at("k").get<int>() / ly;
        s->force_x = [=](double y) { return g * std::sin(kw * y); };
        s->analytic_vx = [=](double y) { return g * std::sin(kw * y) / (nu * kw * kw); };
        s->steady_sine_mode = Scene::SineMode{kw, g / (nu * kw * kw)};
        s->x_invariant = true;
        finish_sound_speed(*s);
        return s;
      });
  ParamSchema periodic = channel_schema();
  periodic.push_back(number_param("amplitude", 5.0, "A in g [1 + A sin(n pi (y - l1)/(l2 - l1))] (par. 6)", {}, {}));
  periodic.push_back(integer_param("n", 4, "n in the periodic force (half-waves across the channel; (D.3) needs an integer)", 1, 1000));
  r.scenes.add({"poiseuille-periodic", "Poiseuille channel driven by the periodic force of par. 6 / App. D", periodic},
               [](const json& p) {
                 auto s = std::make_unique<Scene>(make_channel("poiseuille-periodic", p, ""));
                 const double l1 = s->wall_lo, l2 = s->wall_hi, rho = s->rho0, g = p.at("g").get<double>(),
                              mu = s->phase_viscosity[0], a = p.at("amplitude").get<double>(), n = p.at("n").get<double>();
                 s->force_x = [=](double y) { return g * (1.0 + a * std::sin(n * M_PI * (y - l1) / (l2 - l1))); };
                 s->analytic_vx = [=](double y) { return periodic_force_velocity(y, l1, l2, rho, g, mu, a, n); };
                 finish_sound_speed(*s);
                 return s;
               });
}

}  // namespace closurelab
