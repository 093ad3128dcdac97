// Experiment kind "reduced_model" for every scene: one kind, three reduced models behind it, chosen by
// the cell's top-level "model" or, without one, by the scene:
//   column            the 1D coarse solver across an x-invariant scene (core/reduced/meso_solver.hpp;
//                     experiments/kinds/reduced_model.cpp): the paper's schemes, the force-density balance, transients,
//                     oracles (the default for an x-invariant scene);
//   mesh_2d           the 2D coarse solver of a cellular scene (core/reduced/meso_solver_2d.hpp; reduced_model_2d.cpp)
//                     (the default for a scene with a cellular mode);
//   force_density_2d  the linearised force-density model with solids, walls included, one column for an x-invariant
//                     scene (core/reduced/force_density_2d.hpp; reduced_model_force_density_2d.cpp) (the default for
//                     every other scene: the cylinder lattice, the cylinder channel).
// The cell is validated and run by the chosen model's own kind, the "model" key set aside; a cell without one resolves
// exactly as that kind resolves it (so the committed specs' cell ids do not change), a cell with one keeps it. The
// models' kinds stay registered under their own names (reduced_model_2d, reduced_model_2d_force_density).
#include <array>
#include <string>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/reduced_model.hpp"
#include "experiments/kinds/reduced_model_2d.hpp"
#include "experiments/kinds/cell_config.hpp"

namespace closurelab {

namespace {

constexpr std::array<const char*, 3> kModels{"column", "mesh_2d", "force_density_2d"};

class ReducedModelAnyGeometry : public ExperimentKind {
 public:
  ReducedModelAnyGeometry()
      : column_(make_reduced_model_experiment()),
        mesh_2d_(make_reduced_model_2d_experiment()),
        force_density_2d_(make_reduced_model_force_density_2d_experiment()) {}

  std::string name() const override { return "reduced_model"; }
  std::string description() const override {
    return "a reduced model (coarse balance, deconvolution closure) against the averaged direct SPH of the same box, "
           "with cost and speed-up; the top-level key \"model\" picks it: column (1D across an x-invariant scene; the "
           "default there; the sections below), mesh_2d (2D, cellular scenes; the default there; sections as "
           "reduced_model_2d) or force_density_2d (2D with solids and walls, one column for an x-invariant scene; the "
           "default for the other scenes; sections as reduced_model_2d_force_density)";
  }
  std::vector<KindSection> sections() const override {
    std::vector<KindSection> s = column_->sections();
    s.insert(s.begin(), KindSection{"model", "which reduced model (column, mesh_2d, force_density_2d; default by the scene; echoed only when given)",
                                    "", {}});
    return s;
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    json rest = cell;
    std::string model;
    if (cell.is_object() && cell.contains("model")) {
      if (!cell["model"].is_string()) throw ConfigError(path + "/model", "must be a string (column, mesh_2d, force_density_2d)");
      model = cell["model"].get<std::string>();
      rest.erase("model");
    }
    const ExperimentKind& kind = model.empty() ? default_for(cell, path, reg) : by_name(model, path + "/model");
    json out = kind.resolve(rest, path, reg);
    if (!model.empty()) out["model"] = model;
    return out;
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    json rest = cfg;
    rest.erase("model");
    return chosen(cfg, reg).run(rest, reg, progress);
  }

  // The chosen model's upgrade (a stored row whose scene no registry knows is compared as stored).
  json upgraded_params(json stored) const override {
    json rest = stored;
    rest.erase("model");
    try {
      json out = chosen(stored, builtin_registry()).upgraded_params(std::move(rest));
      if (stored.contains("model")) out["model"] = stored["model"];
      return out;
    } catch (const ConfigError&) {
      return stored;
    }
  }

  // Only the order matters: a scene only the user's registry knows takes the column's estimate.
  double expected_cost(const json& cfg) const override {
    json rest = cfg;
    rest.erase("model");
    try {
      return chosen(cfg, builtin_registry()).expected_cost(rest);
    } catch (const ConfigError&) {
      return column_->expected_cost(rest);
    }
  }

 private:
  const ExperimentKind& by_name(const std::string& model, const std::string& path) const {
    if (model == kModels[0]) return *column_;
    if (model == kModels[1]) return *mesh_2d_;
    if (model == kModels[2]) return *force_density_2d_;
    throw ConfigError(path, "unknown reduced model '" + model + "'; known: column, mesh_2d, force_density_2d");
  }
  // The scene decides: x-invariant, the column; a cellular mode, the 2D mesh; otherwise the model with solids.
  const ExperimentKind& default_for(const json& cell, const std::string& path, const Registry& reg) const {
    const auto scene = build_scene(cell, path, reg, nullptr);
    if (scene->x_invariant) return *column_;
    if (scene->cellular_mode) return *mesh_2d_;
    return *force_density_2d_;
  }
  const ExperimentKind& chosen(const json& cfg, const Registry& reg) const {
    if (cfg.contains("model")) return by_name(cfg["model"].get<std::string>(), "/model");
    return default_for(cfg, "", reg);
  }

  std::unique_ptr<ExperimentKind> column_, mesh_2d_, force_density_2d_;
};

}  // namespace

std::unique_ptr<ExperimentKind> make_reduced_model_any_geometry_experiment() {
  return std::make_unique<ReducedModelAnyGeometry>();
}

}  // namespace closurelab
