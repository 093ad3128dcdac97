// The 2D force-density model's solver section (schema, reader), its meshes and the checks a spec is validated by
// before anything runs (core/reduced/force_density_2d.hpp); the solver itself is force_density_2d.cpp.
#include <cmath>

#include "core/base/errors.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/reduced/meso_solver_2d.hpp"

namespace closurelab {

ParamSchema force_density_2d_schema() {
  const ForceDensity2DOptions d;  // the defaults
  return {number_param("spacing_over_eta", d.spacing_over_eta, "coarse mesh spacing Delta / eta'", 0.05, 4.0),
          integer_param("reconstruction_refinement", d.reconstruction_refinement,
                        "the reconstruction mesh's spacing is Delta / this (1: the coarse mesh)", 1, 16),
          number_param("window_cutoff", d.window_cutoff,
                       "window values below this fraction of psi(0) are dropped from the assembled maps", 0.0, 1e-3),
          number_param("hold_fraction", d.hold_fraction,
                       "coarse nodes whose window's fluid mass fraction is below this are held: not evolved, not "
                       "deconvolution data",
                       0.0, 0.5),
          string_param("held_node_value", name_of(d.held_node_value),
                       "what a held node reports: imposed (zero) or reconstructed (the average of the reconstruction)",
                       names_of<HeldNodeValue>())};
}

ForceDensity2DOptions force_density_2d_options_from(const json& s) {
  ForceDensity2DOptions o;
  o.spacing_over_eta = s.at("spacing_over_eta").get<double>();
  o.reconstruction_refinement = s.at("reconstruction_refinement").get<int>();
  o.window_cutoff = s.at("window_cutoff").get<double>();
  o.hold_fraction = s.at("hold_fraction").get<double>();
  o.held_node_value = parse_name<HeldNodeValue>(s.at("held_node_value").get<std::string>(), "/solver/held_node_value");
  return o;
}

TensorMesh2D force_density_coarse_mesh(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta) {
  if (!scene.box.periodic_x || !scene.box.periodic_y || scene.has_walls)
    throw ConfigError("/scene", "the 2D force-density model needs a doubly periodic box (solids given by position); "
                                "scene '" + scene.name + "' is not one");
  return coarse_mesh_2d(scene, kernel, spacing_over_eta);  // the 2D reduced model's periodic mesh
}

TensorMesh2D force_density_reconstruction_mesh(const Scene& scene, const TensorMesh2D& coarse, int refinement) {
  const int nx = coarse.nx() * refinement, ny = coarse.ny() * refinement;
  if (nx > scene.nx || ny > scene.ny)
    throw ConfigError("/solver/reconstruction_refinement",
                      "the reconstruction mesh (" + std::to_string(nx) + " x " + std::to_string(ny) +
                          ") is finer than the particle lattice (" + std::to_string(scene.nx) + " x " +
                          std::to_string(scene.ny) + "); lower the refinement");
  return {UniformMesh1D::cell_centred(0.0, scene.box.lx, nx, true),
          UniformMesh1D::cell_centred(0.0, scene.box.ly, ny, true)};
}

void check_force_density_2d(const Scene& scene, const AveragingKernel& kernel, const ForceDensity2DOptions& o) {
  const TensorMesh2D coarse = force_density_coarse_mesh(scene, kernel, o.spacing_over_eta);
  force_density_reconstruction_mesh(scene, coarse, o.reconstruction_refinement);
  if (scene.van_der_waals)
    throw ConfigError("/scene", "the 2D force-density model linearises a weakly compressible equation of state; "
                                "scene '" + scene.name + "' uses van der Waals");
  if (std::abs(scene.box.lx / scene.nx - scene.dx) > 1e-12 * scene.dx ||
      std::abs(scene.box.ly / scene.ny - scene.dx) > 1e-12 * scene.dx)
    throw ConfigError("/scene", "the 2D force-density model needs the square lattice to fill the periodic box");
}

void check_force_density_closure(const json& deconvolver, const std::string& path) {
  const std::string name = deconvolver.value("name", "");
  if (name == "cg" || name == "cgls")
    throw ConfigError(path + "/closure/deconvolver", "the steady solve probes the closure once, which needs it "
                                                     "linear in the data; " + closure_nonlinearity(deconvolver));
  if (deconvolver.value("regularizer", "identity") != "identity")
    throw ConfigError(path + "/closure/deconvolver/regularizer",
                      "the velocity's unknowns are the reconstruction nodes outside the solid, not a tensor mesh: "
                      "difference regularizers do not apply (use identity)");
}

}  // namespace closurelab
