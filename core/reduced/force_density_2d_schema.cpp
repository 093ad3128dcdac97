// The 2D force-density model's solver section (schema, reader), its meshes and the checks a spec is validated by
// before anything runs (core/reduced/force_density_2d.hpp); the solver itself is force_density_2d.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/option_table.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/reduced/reduced_grid.hpp"

namespace closurelab {

namespace {

const OptionTable<ForceDensity2DOptions>& force_density_2d_options() {
  using O = ForceDensity2DOptions;
  static const OptionTable<O> table =
      OptionTable<O>("/solver")
          .number("spacing_over_eta", &O::spacing_over_eta, "coarse mesh spacing Delta / eta'", 0.05, 4.0)
          .integer("reconstruction_refinement", &O::reconstruction_refinement,
                   "the reconstruction mesh's spacing is Delta / this (1: the coarse mesh; 0: the particle "
                   "lattice's rows and columns, one column for an x-invariant scene)",
                   0, 16)
          .choice("reconstruction_y_nodes", &O::reconstruction_y_nodes,
                  "along a walled y (reconstruction_refinement >= 1): the reconstruction's nodes cell-centred "
                  "across the box (a wall surface on a cell face), on_wall_surfaces (the coarse rows refined, "
                  "continued into the walls) or lattice_rows (the particle lattice's rows, the columns still "
                  "Delta / refinement)")
          .number("window_cutoff", &O::window_cutoff,
                  "window values below this fraction of psi(0) are dropped from the assembled maps", 0.0, 1e-3)
          .number("hold_fraction", &O::hold_fraction,
                  "coarse nodes whose window's fluid mass fraction is below this are held: not evolved, not "
                  "deconvolution data",
                  0.0, 0.5)
          .choice("held_node_value", &O::held_node_value,
                  "what a held node reports: imposed (zero) or reconstructed (the average of the reconstruction)")
          .boolean("convective_stress", &O::convective_stress,
                   "add the averaged convective flux -div sum m V V psi of the reconstructed particle velocities "
                   "(for Re not small; not for an x-invariant scene); the steady state then by Newton's method")
          .choice("pair_forces", &O::pair_forces,
                  "whose pair forces the model linearises on the lattice: standard ((5.1), the solids at zero "
                  "velocity) or transport_velocity (Adami, Hu & Adams: the viscous term with eps = 0.01 h^2, the "
                  "generalized wall condition's ghost velocity and extrapolated pressure on the solids), for a "
                  "reference computed under that formulation")
          .number("newton_tolerance", &O::newton_tolerance,
                  "with convective_stress: Newton stops when its step is below this fraction of the state (max norms)",
                  1e-15, 1e-2)
          .integer("newton_max_iterations", &O::newton_max_iterations,
                   "with convective_stress: Newton's steps at most (numerical_issue beyond)", 1, 200)
          .unbound(entry_param(
              "time_integration", "newton",
              "newton: the steady state by the model's own solve (the probed affine rate bordered by the total "
              "density deviation; Newton's iteration with convective_stress); any other registered integrator "
              "(closurelab list integrator) marches the state from rest to mode's end, the closure applied at every "
              "rate evaluation (arkode_imex: the pair forces' linear maps implicit, the body force and the "
              "convective flux explicit)"))
          .number("kappa", &O::kappa,
                  "marched: the loop's step kappa min(rho0 Delta^2/mu, Delta/(c + max|v|)) ((5.21)-(5.22) with the "
                  "sound speed; an ARKODE integrator steps inside it as its error control needs)",
                  0.0, 1e3, true)
          .time_loop();
  return table;
}

}  // namespace

ParamSchema force_density_2d_schema() { return force_density_2d_options().schema(); }

ForceDensity2DOptions force_density_2d_options_from(const json& s) { return force_density_2d_options().read(s); }

namespace {

// The scene's key that sets eta' ("eta_over_l", "eta_over_ly", ...), for messages.
std::string eta_key(const Scene& scene) {
  if (scene.params.is_object())
    for (const auto& [key, value] : scene.params.items())
      if (key.rfind("eta_over", 0) == 0) return "/scene/" + key;
  return "/scene (its eta')";
}

// A coarse mesh finer than the particle lattice averages nothing the particles resolve, and at a tiny eta' its
// node count outgrows an int (n = 32, eta' = 1e-6 L: 1e12 nodes, which wrapped to 1410065408 and crashed). Its
// spacing along each resolved side is computed in double from the counts the mesh would get, before any int.
void check_coarse_not_finer_than_lattice(const Scene& scene, double target) {
  const auto spacing = [&](double length) { return length / std::max(1.0, std::round(length / target)); };
  double finest = std::numeric_limits<double>::infinity();
  double nodes = 1.0;
  if (!scene.x_invariant) {
    finest = std::min(finest, spacing(scene.box.lx));
    nodes *= std::round(scene.box.lx / target);
  }
  const double along_y = scene.box.periodic_y ? scene.box.ly : scene.wall_hi - scene.wall_lo;
  finest = std::min(finest, spacing(along_y));
  nodes *= std::round(along_y / target) + (scene.box.periodic_y ? 0.0 : 1.0);
  if (!(target > 0) || !(finest >= scene.dx * (1.0 - 1e-9))) {
    std::ostringstream os;
    os.precision(4);
    os << "the coarse mesh (spacing " << target << " = spacing_over_eta x eta', about " << nodes
       << " nodes) is finer than the particle lattice (spacing " << scene.dx << ", " << scene.nx << " x " << scene.ny
       << " particles): the averages cannot resolve what the particles do not; raise " << eta_key(scene)
       << " or spacing_over_eta to a coarse spacing of at least " << scene.dx;
    throw ConfigError("/solver/spacing_over_eta", os.str());
  }
}

}  // namespace

TensorMesh2D force_density_coarse_mesh(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta) {
  if (!scene.box.periodic_x)
    throw ConfigError("/scene",
                      "the 2D force-density model needs a box periodic in x; scene '" + scene.name + "' is not");
  if (scene.box.periodic_y == scene.has_walls)
    throw ConfigError("/scene",
                      "the 2D force-density model needs a box periodic in y or bounded by walls in y; scene '" +
                          scene.name + "' is neither");
  const double target = spacing_over_eta * kernel.eta();
  check_coarse_not_finer_than_lattice(scene, target);
  // x: one column for an x-invariant scene (its fields have no x-structure to resolve), else cell-centred.
  // One column, as the 1D model's (core/reduced/reduced_grid.hpp).
  UniformMesh1D x{0.0, scene.box.lx, 1, true, scene.box.lx};
  if (!scene.x_invariant) {
    const int nx = static_cast<int>(std::lround(scene.box.lx / target));
    if (nx < 4)
      throw ConfigError("/solver/spacing_over_eta",
                        "fewer than 4 coarse nodes along x (" + std::to_string(nx) + "); lower spacing_over_eta");
    x = UniformMesh1D::cell_centred(0.0, scene.box.lx, nx, true);
  }
  if (scene.box.periodic_y) {
    const int ny = static_cast<int>(std::lround(scene.box.ly / target));
    if (ny < 4)
      throw ConfigError("/solver/spacing_over_eta",
                        "fewer than 4 coarse nodes along y (" + std::to_string(ny) + "); lower spacing_over_eta");
    return {x, UniformMesh1D::cell_centred(0.0, scene.box.ly, ny, true)};
  }
  // Walls in y: the 1D model's nodes, on both wall surfaces and evenly between ((5.6); reduced_grid.cpp).
  return {x, wall_to_wall_nodes(scene, target)};
}

TensorMesh2D force_density_reconstruction_mesh(const Scene& scene, const TensorMesh2D& coarse, int refinement,
                                               ReconstructionYNodes y_nodes) {
  // x: the coarse columns refined (one column stays one: an x-invariant reconstruction); y: periodic, the coarse
  // rows refined; walled, across the whole box (walls included) at the coarse spacing / refinement, cell-centred or
  // on the coarse rows (so on both wall surfaces) and continued at that spacing into the walls, or on the lattice's
  // rows.
  // Refinement 0: the lattice's own columns and rows (the particles read their own node).
  const bool lattice = refinement == 0;
  if (!lattice && !scene.box.periodic_y && y_nodes == ReconstructionYNodes::on_wall_surfaces) {
    const int nx = coarse.nx() == 1 ? 1 : coarse.nx() * refinement;
    const double s = coarse.y.spacing / refinement;
    const int below = static_cast<int>(std::floor(coarse.y.origin / s + 1e-9));  // nodes inside the lower wall
    const double origin = coarse.y.origin - below * s;
    const int ny = static_cast<int>(std::floor((scene.box.ly - origin) / s + 1e-9)) + 1;
    if (nx > scene.nx || s < scene.dx)
      throw ConfigError("/solver/reconstruction_refinement",
                        "the reconstruction mesh (spacing " + std::to_string(s) +
                            ") is finer than the particle lattice (" + std::to_string(scene.dx) +
                            "); lower the refinement");
    return {UniformMesh1D::cell_centred(0.0, scene.box.lx, nx, true), UniformMesh1D{origin, s, ny, false, 0.0}};
  }
  const bool lattice_rows = !scene.box.periodic_y && y_nodes == ReconstructionYNodes::lattice_rows;
  const int nx = coarse.nx() == 1 ? 1 : lattice ? scene.nx : coarse.nx() * refinement;
  const int ny = lattice || lattice_rows ? scene.ny
                 : scene.box.periodic_y  ? coarse.ny() * refinement
                                         : static_cast<int>(std::lround(scene.box.ly * refinement / coarse.y.spacing));
  if (nx > scene.nx || ny > scene.ny)
    throw ConfigError("/solver/reconstruction_refinement",
                      "the reconstruction mesh (" + std::to_string(nx) + " x " + std::to_string(ny) +
                          ") is finer than the particle lattice (" + std::to_string(scene.nx) + " x " +
                          std::to_string(scene.ny) + "); lower the refinement");
  return {UniformMesh1D::cell_centred(0.0, scene.box.lx, nx, true),
          UniformMesh1D::cell_centred(0.0, scene.box.ly, ny, scene.box.periodic_y)};
}

void check_force_density_2d(const Scene& scene, const AveragingKernel& kernel, const ForceDensity2DOptions& o) {
  const TensorMesh2D coarse = force_density_coarse_mesh(scene, kernel, o.spacing_over_eta);
  const TensorMesh2D recon =
      force_density_reconstruction_mesh(scene, coarse, o.reconstruction_refinement, o.reconstruction_y_nodes);
  check_force_density_2d_memory(coarse.size(), recon.size(), scene.x_invariant, "/solver/spacing_over_eta");
  // The pressure is linearised about the lattice with one dP/dn for every pair, which a van der Waals equation of
  // state with its own cross-phase attraction (7.1) does not have; in an x-invariant flow the density deviation stays
  // uniform (ṅ cancels pair by pair along each row), so the pressure's linearisation is never used there.
  if (scene.van_der_waals && !scene.x_invariant)
    throw ConfigError("/scene",
                      "the 2D force-density model linearises the pressure with one dP/dn for every pair; scene '" +
                          scene.name + "' uses van der Waals and is not x-invariant");
  if (std::abs(scene.box.lx / scene.nx - scene.dx) > 1e-12 * scene.dx ||
      std::abs(scene.box.ly / scene.ny - scene.dx) > 1e-12 * scene.dx)
    throw ConfigError("/scene", "the 2D force-density model needs the square lattice to fill the periodic box");
  if ((scene.has_walls || scene.solid_at) && scene.wall_model != WallModel::zero_velocity)
    throw ConfigError("/scene/wall_model",
                      "the 2D force-density model holds the solids at their known zero velocity; "
                      "use zero_velocity walls and solids (for a no-slip condition continued "
                      "into the solid: solver.pair_forces transport_velocity, the generalized "
                      "wall condition linearised)");
  if (scene.solid_velocity)
    throw ConfigError(
        "/scene", "the 2D force-density model holds the solids at rest; scene '" + scene.name + "' moves its walls");
  if (o.convective_stress && scene.x_invariant)
    throw ConfigError("/solver/convective_stress",
                      "scene '" + scene.name +
                          "' is x-invariant: its convective flux has no divergence (V_y = 0, nothing varies along x)");
  // The pair forces are linearised about the lattice's uniform number density: every solid particle a fluid particle
  // reaches must itself see a full stencil, so a wall must be two SPH supports thick.
  const double support = scene.smoothing_kernel().support();
  if (scene.has_walls && std::min(scene.wall_lo, scene.box.ly - scene.wall_hi) < 2.0 * support)
    throw ConfigError("/scene", "the walls are thinner than two SPH supports (" + std::to_string(2.0 * support) +
                                    "): the solid particles next to the fluid would not see a full lattice; raise "
                                    "eta_over_ly or n_y");
}

void check_force_density_closure(const json& deconvolver, const std::string& path, bool steady) {
  const std::string name = deconvolver.value("name", "");
  if (steady && (name == "cg" || name == "cgls"))
    throw ConfigError(path + "/closure/deconvolver",
                      "the steady solve probes the closure once, which needs it linear in the data; " +
                          closure_nonlinearity(deconvolver));
  const std::string regularizer = deconvolver.value("regularizer", "identity");
  if (regularizer != "identity" && regularizer != "first_difference_zero_ends")
    throw ConfigError(path + "/closure/deconvolver/regularizer",
                      "the velocity's unknowns are the reconstruction nodes outside the solid, not a tensor mesh: use "
                      "identity, or first_difference_zero_ends (the viscosity-weighted first difference over the "
                      "reconstruction mesh's links, those into the solid to its known zero)");
}

}  // namespace closurelab
