#pragma once
// A scene (DESIGN.md §1, §5): geometry, walls, phases, body force, the SPH discretization, the stress
// components the engine must compute, and the analytic steady solution where one exists.
// Scenes are registered by name in the registry's "scene" family (core/scenes/scenes.cpp).
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/sph/equation_of_state.hpp"
#include "core/base/enum_names.hpp"
#include "core/base/mesh.hpp"
#include "core/base/params.hpp"
#include "core/sph/particles.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab {

enum class WallModel {
  zero_velocity,   // (5.3): wall particles at rest, used as they are in the pair forces
  ghost_velocity,  // Morris et al. (1997): in a fluid–wall pair the wall particle carries −(d_wall/d_fluid) v_fluid
};
template <>
struct EnumNames<WallModel> {
  static constexpr std::array<std::pair<WallModel, std::string_view>, 2> table{
      {{WallModel::zero_velocity, "zero_velocity"}, {WallModel::ghost_velocity, "ghost_velocity"}}};
};

struct Scene {
  std::string name;
  json params;  // the resolved scene parameters, echoed into every output

  // Geometry: box [0, lx) x [0, ly), square lattice of spacing dx (ε'), nx by ny particles.
  PeriodicBox box;
  int nx = 0, ny = 0;
  double dx = 0.0;
  double eta = 0.0;  // η', the averaging scale; walls are 3η' thick (5.3)
  bool has_walls = false;
  double wall_lo = 0.0, wall_hi = 0.0;  // l1, l2 of (5.15)
  // Solids besides the walls in y (a boundary component given by position, e.g. the cylinders of a porous
  // medium): the lattice particles where solid_at(x, y) holds are held fixed like wall particles, at zero velocity
  // (5.3) or, under the ghost-velocity model with solid_depth set, carrying ghost velocities in fluid–solid pairs.
  // Empty: none.
  std::function<bool(double x, double y)> solid_at;
  // Under the ghost-velocity model, how deep a point lies inside a solid of solid_at, to its nominal surface
  // (negative in the fluid): the d_wall and −d_fluid of a fluid–solid pair. Empty: the model's distances are to the
  // walls in y, and the solids of solid_at are held at zero velocity whatever the model.
  std::function<double(double x, double y)> solid_depth;
  // The prescribed velocity of the fixed particles at their sites (a moving wall: the cavity's lid), set by
  // make_particles(); empty: at rest. The walls of either formulation move with it (the zero-velocity model's
  // wall particles carry it in the pair forces, the transport-velocity condition's ghost velocity is 2 v_w − ṽ_w).
  std::function<Vec2(double x, double y)> solid_velocity;
  // The scene is meant for the transport-velocity formulation only (the lid-driven cavity): the standard one is
  // refused at validation (check_direct_run).
  bool needs_transport_velocity = false;
  WallModel wall_model = WallModel::zero_velocity;
  double ghost_beta_max = 0.0;

  // Material and forcing (model units).
  double rho0 = 1.0;
  std::vector<double> phase_viscosity{1.0};
  // The phase at height y (index into phase_viscosity), for fluid and wall particles alike (walls take the
  // phase of the fluid next to them). Empty: phase 0 everywhere.
  std::function<int(double y)> phase_at;
  // Heights of the phase interfaces inside the channel (between lattice rows), ascending; empty if one phase.
  std::vector<double> interfaces;
  // μ_ij of (5.1) for unlike particles (core/sph/sph_pair_force.hpp).
  PairViscosityMean pair_viscosity_mean = PairViscosityMean::arithmetic;
  std::function<double(double y)> force_x;  // body force per unit mass along x
  // Scenes whose force depends on x as well (not x-invariant) declare the whole body force per unit mass at a
  // point instead; when set, the engine uses it and ignores force_x.
  std::function<Vec2(double x, double y)> body_force;
  // The initial velocity of the moving particles at their sites (empty: at rest), set by make_particles().
  std::function<Vec2(double x, double y)> initial_velocity;
  // A random shift of every particle off its lattice site, as a fraction of dx (0: the lattice; make_particles()):
  // x += ξ p dx, y += ζ p dx with ξ, ζ uniform in [0, 1), drawn as PySPH's taylor_green.py --perturb p draws them
  // (numpy.random.seed(1), all ξ in lattice order, then all ζ; core/base/numpy_uniform.hpp), before the initial
  // velocity is set at the shifted sites. Scenes with fixed particles keep it 0.
  double position_perturbation = 0.0;

  // SPH discretization.
  SmoothingKernel::Type smoothing_type = SmoothingKernel::Type::quintic;
  double h = 0.0;            // smoothing length
  SmoothingKernel smoothing_kernel() const { return SmoothingKernel(smoothing_type, h); }
  double sound_speed = 0.0;  // >= 10x the peak velocity
  // Equation of state: the weakly compressible P = c²(m n − ρ0) + background_pressure unless van_der_waals
  // is set (7.1) (core/sph/equation_of_state.hpp).
  double background_pressure = 0.0;
  std::optional<VanDerWaalsEos> van_der_waals;

  // The flow is x-invariant (fields depend on y only).
  bool x_invariant = true;

  // The analytic steady velocity v_x(y) where known (empty otherwise), and its peak.
  std::function<double(double y)> analytic_vx;
  double analytic_peak = 0.0;
  // A channel driven by a uniform force g along x (poiseuille-uniform): its analytic profile is a parabola, so the
  // direct SPH's effective walls are the roots of a parabola fitted to the particles, and its convective stress has
  // the closed form of App. B (both reported by sph_validation).
  std::optional<double> uniform_force_x;
  // Scenes whose steady solution is a single sine mode v_x = amplitude · sin(wavenumber · y) (kolmogorov) say
  // so: the reduced model then compares its steady amplitude with the Landweber prediction (DESIGN.md §5).
  struct SineMode {
    double wavenumber = 0.0;  // radians per unit length
    double amplitude = 0.0;
  };
  std::optional<SineMode> steady_sine_mode;
  // Cellular flow (not x-invariant; core/scenes/analytic.hpp): at every time t the exact velocity is
  // amplitude(t) · (sin kx' cos ky', −cos kx' sin ky') with x' = x + offset, y' = y + offset, k the wavenumber,
  // relaxing from the initial to the steady amplitude at the rate 2 k² ν (a Taylor–Green vortex decays when
  // unforced; the taylor-green scene's vortex is this mode with offset L/4).
  struct CellularMode {
    double wavenumber = 0.0;         // k = 2π m / L, radians per unit length
    double steady_amplitude = 0.0;   // g / (2 k² ν); 0 when unforced
    double initial_amplitude = 0.0;  // 0: from rest
    double decay_rate = 0.0;         // 2 k² ν
    double offset = 0.0;             // the shift of both coordinates
    double amplitude(double t) const {
      return steady_amplitude + (initial_amplitude - steady_amplitude) * std::exp(-decay_rate * t);
    }
  };
  std::optional<CellularMode> cellular_mode;
  // The Taylor–Green vortex of the "taylor-green" scene (core/scenes/taylor_green_scene.cpp; PySPH's
  // taylor_green.py): in a doubly periodic box of side L, with k = 2π/L and b = −2k²ν (= −8π²/Re at L = U = 1),
  //   u = −U e^{bt} cos kx sin ky,  v = U e^{bt} sin kx cos ky,  p = −¼ ρ U² e^{2bt} (cos 2kx + cos 2ky),
  // an exact solution of the incompressible Navier–Stokes equations; the largest |v| over the box is U e^{bt}.
  struct TaylorGreenVortex {
    double wavenumber = 0.0;  // k
    double velocity = 0.0;    // U
    double decay_rate = 0.0;  // −b = 2 k² ν
    double density = 1.0;     // ρ of the pressure
    double factor(double t) const { return velocity * std::exp(-decay_rate * t); }
    Vec2 velocity_at(double x, double y, double t) const {
      const double f = factor(t);
      return {-f * std::cos(wavenumber * x) * std::sin(wavenumber * y), f * std::sin(wavenumber * x) * std::cos(wavenumber * y)};
    }
    double pressure_at(double x, double y, double t) const {
      const double f = factor(t);
      return -0.25 * density * f * f * (std::cos(2.0 * wavenumber * x) + std::cos(2.0 * wavenumber * y));
    }
    double max_speed(double t) const { return factor(t); }
  };
  std::optional<TaylorGreenVortex> taylor_green;
  // The lid-driven cavity (core/scenes/cavity_scene.cpp; PySPH's cavity.py): the fluid fills the square
  // [origin, origin + side]² inside walls on all four sides, the top wall (y > origin + side) slides along x at the
  // lid speed; Re = lid speed × side / ν. Its reference is the steady centre-line profiles of Ghia, Ghia & Shin
  // (1982) (experiments/kinds/cavity_validation.cpp).
  struct LidDrivenCavity {
    double side = 1.0, origin = 0.0, lid_speed = 1.0, reynolds = 100.0;
  };
  std::optional<LidDrivenCavity> cavity;
  // Flow through a porous medium (cylinder-lattice; core/scenes/cylinder_lattice_scene.hpp): the number wanted is
  // the Darcy permeability k = μ ⟨u_x⟩ / (ρ g), ⟨u_x⟩ the x-velocity averaged over the whole periodic cell (the
  // solid counting zero) and g the body force per unit mass on the fluid; the scene states its reference value.
  struct Permeability {
    double reference = 0.0;        // k (length²)
    double body_force = 0.0;       // g along x, per unit mass, on the fluid particles only
    double solid_fraction = 0.0;   // c, the solid's share of the cell's area
    std::string reference_source;  // how the reference was computed
    // The solid's size (the cylinder radius) and, for a measured k, the size whose reference permeability is k:
    // how far the discrete solid's effective surface lies from the nominal one (empty: not offered).
    double solid_size = 0.0;
    std::function<double(double k)> solid_size_for;
    // ρ g k / μ: the superficial velocity ⟨u_x⟩ the reference predicts.
    double superficial_velocity(double rho, double mu) const { return rho * body_force * reference / mu; }
  };
  std::optional<Permeability> permeability;

  // The time unit τ of a transient's snapshot times t/τ (the reduced models' `transient.t_over_tau`): the
  // cellular mode's decay time 1/(2k²ν) where the scene has one, else the advective time L/v_max, L the channel's
  // width between the wall surfaces (the cavity's side L; L_y without walls) and v_max the analytic peak (the lid
  // speed); 0 when the scene has neither.
  double time_scale() const;

  bool is_wall(double y) const { return has_walls && (y < wall_lo || y > wall_hi); }
  // A lattice particle at (x, y) is held fixed: inside a wall in y or a solid of solid_at.
  bool is_solid(double x, double y) const { return is_wall(y) || (solid_at && solid_at(x, y)); }
  // The regions of the error tables (one definition): fluid, strictly between the wall surfaces (a node on a
  // wall surface carries the imposed v̄ = 0 of (5.6)); interior, at least 3η' from both wall surfaces; the wall
  // band, fluid and not interior. Without walls every point is fluid and interior. A point within 1e-12 L_y of
  // a region's edge counts as on it (nodes placed at l1 + 3η' by arithmetic are interior).
  bool in_fluid(double y) const;
  bool in_interior(double y) const;
  bool in_wall_band(double y) const { return in_fluid(y) && !in_interior(y); }
  // For an x-invariant scene, the same scene on the narrowest periodic strip the SPH engine accepts (3 supports
  // plus the list skin): per-unit-length quantities (averages with periodic images, pair sums per column) are
  // the same on it; otherwise the scene itself.
  Scene narrowest_strip() const;
  // Lattice particles: (i + 1/2) dx, (j + 1/2) dx; walls and solids (is_solid) held fixed; mass so that the SPH density
  // is rho0 (or rho0 dx² where mass_from_cell_volume is set); shifted by position_perturbation where it is set.
  ParticleSystem make_particles() const;
  // The particle mass rho0 dx² (PySPH's examples: ρ0 times the lattice cell's area) instead of rho0 / n0, n0 the
  // lattice's summation number density (whose SPH density at rest is exactly rho0).
  bool mass_from_cell_volume = false;
  double particle_mass() const;
  double max_viscosity() const;
  int phase(double y) const { return phase_at ? phase_at(y) : 0; }
  // Viscosity of the phase at a point (single-phase scenes: the one phase).
  double viscosity_at(const Vec2& point) const;
  // The pressure of a particle of mass m at number density n in a like pair (k_ij = 1 in (7.1)).
  double pressure(double n, double mass) const {
    return van_der_waals ? van_der_waals->pressure(n, 1.0)
                         : weakly_compressible_pressure(mass * n, rho0, sound_speed, background_pressure);
  }
  // What an unlike pair adds to each of P_i/n_i² and P_j/n_j² in (5.1): (1 − k*) c_2 under (7.1), else 0.
  double unlike_pair_excess_over_n2() const { return van_der_waals ? van_der_waals->unlike_excess_over_n2() : 0.0; }
  // The lattice number density n* = rho0 / m and the constant pressure P* = P(n*) of the incompressible
  // closure (§5.2: positions are kept intact), of like pairs.
  double lattice_number_density() const { return rho0 / particle_mass(); }
  double rest_pressure() const {
    if (!van_der_waals) return background_pressure;
    const double m = particle_mass();
    return van_der_waals->pressure(rho0 / m, 1.0);
  }
};

// Scene parameters shared by the scene schemas: the wall model (walled scenes) and the SPH discretization.
ParamSchema wall_model_params();
// A stored scene section from before a parameter was added, with the value that reproduces the earlier behaviour
// (ExperimentKind::upgraded_params): cylinder-lattice's wall_model and ghost_beta_max (solids at zero velocity).
json upgraded_scene_params(json scene);
ParamSchema sph_discretization_params();  // smoothing_kernel, h_over_dx, sound_speed_factor
// Reads smoothing_kernel and h_over_dx of a resolved scene section (path: its JSON path) into a scene whose dx
// is set.
void read_sph_discretization(Scene& scene, const json& resolved, const std::string& path);
// A periodic strip must hold 3 SPH supports plus the list skin (ConfigError at path/n_x otherwise).
void check_strip_width(const Scene& scene, const std::string& path);

}  // namespace closurelab
