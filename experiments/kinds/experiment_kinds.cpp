#include <stdexcept>

#include "core/base/errors.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/quadrature_convergence.hpp"
#include "experiments/kinds/reduced_model.hpp"
#include "experiments/kinds/reduced_model_2d.hpp"
#include "experiments/kinds/snapshot_closure.hpp"
#include "experiments/kinds/sph_validation.hpp"
#include "experiments/kinds/stability_experiment.hpp"

namespace closurelab {

const std::vector<std::unique_ptr<ExperimentKind>>& experiment_kinds() {
  static const std::vector<std::unique_ptr<ExperimentKind>> kinds = [] {
    std::vector<std::unique_ptr<ExperimentKind>> k;
    k.push_back(make_sph_validation_experiment());
    k.push_back(make_stability_experiment());
    k.push_back(make_quadrature_convergence_experiment());
    k.push_back(make_reduced_model_any_geometry_experiment());  // "reduced_model": the three below by "model"
    k.push_back(make_reduced_model_2d_experiment());
    k.push_back(make_reduced_model_force_density_2d_experiment());
    k.push_back(make_snapshot_closure_experiment());
    return k;
  }();
  return kinds;
}

json ExperimentKind::upgraded_params(json stored) const {
  if (stored.is_object() && stored.contains("scene")) stored["scene"] = upgraded_scene_params(stored["scene"]);
  // The Landweber series' lift, added since: rows before it ran the series on a square operator (lift none); the
  // stability kind's `method`, every other kind's `closure.deconvolver` (the reduced kinds apply this first).
  const auto lift = [](json& d) {
    if (d.is_object() && d.value("name", "") == "landweber" && !d.contains("lift")) d["lift"] = "none";
  };
  if (stored.is_object() && stored.contains("method")) lift(stored["method"]);
  if (stored.is_object() && stored.contains("closure") && stored["closure"].is_object() &&
      stored["closure"].contains("deconvolver"))
    lift(stored["closure"]["deconvolver"]);
  return stored;
}

double ExperimentKind::expected_cost(const json& resolved) const {
  auto positive = [](const json& obj, const char* key) {
    return obj.is_object() && obj.contains(key) && obj[key].is_number() && obj[key].get<double>() > 0 ? obj[key].get<double>() : 1.0;
  };
  const json scene = resolved.value("scene", json()), solver = resolved.value("solver", json());
  const double n_y = positive(scene, "n_y");
  const bool to_time = solver.is_object() && solver.value("mode", "") == "target_time";
  return n_y * n_y * n_y * positive(solver, to_time ? "target_time" : "max_time");
}

namespace {

const ExperimentKind& find_among(const std::vector<const ExperimentKind*>& kinds, const std::string& name,
                                 const std::string& path) {
  std::string known;
  for (const ExperimentKind* k : kinds) {
    if (k->name() == name) return *k;
    known += (known.empty() ? "" : ", ") + k->name();
  }
  throw ConfigError(path, "unknown experiment kind '" + name + "'; known: " + known);
}

}  // namespace

const ExperimentKind& find_experiment_kind(const std::string& name, const std::string& path) {
  std::vector<const ExperimentKind*> builtins;
  for (const auto& k : experiment_kinds()) builtins.push_back(k.get());
  return find_among(builtins, name, path);
}

void add_experiment_kind(Registry& registry, std::unique_ptr<ExperimentKind> kind) {
  if (!kind) throw std::logic_error("registry: add_experiment_kind needs a kind");
  for (const ExperimentKind* k : known_experiment_kinds(registry))
    if (k->name() == kind->name())
      throw std::logic_error("registry: experiment '" + kind->name() + "' is registered twice");
  registry.experiment_kinds.push_back(std::move(kind));
}

std::vector<const ExperimentKind*> known_experiment_kinds(const Registry& registry) {
  std::vector<const ExperimentKind*> kinds;
  for (const auto& k : experiment_kinds()) kinds.push_back(k.get());
  for (const auto& k : registry.experiment_kinds) kinds.push_back(k.get());
  return kinds;
}

const ExperimentKind& find_experiment_kind(const Registry& registry, const std::string& name, const std::string& path) {
  return find_among(known_experiment_kinds(registry), name, path);
}

}  // namespace closurelab
