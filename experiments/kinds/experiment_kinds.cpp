#include "core/base/registry.hpp"
#include "experiments/kinds/coarse_continuum.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/quadrature_convergence.hpp"
#include "experiments/kinds/reduced_model.hpp"
#include "experiments/kinds/reduced_model_2d.hpp"
#include "experiments/kinds/snapshot_closure.hpp"
#include "experiments/kinds/sph_validation.hpp"
#include "experiments/kinds/stability_experiment.hpp"

namespace closurelab {

void register_builtin_experiments(Registry& r) {
  if (r.experiments.contains("reduced_model")) return;  // already registered
  r.experiments.add(make_sph_validation_experiment());
  r.experiments.add(make_stability_experiment());
  r.experiments.add(make_quadrature_convergence_experiment());
  r.experiments.add(make_reduced_model_any_geometry_experiment());  // "reduced_model": the three below by "model"
  r.experiments.add(make_reduced_model_2d_experiment());
  r.experiments.add(make_reduced_model_force_density_2d_experiment());
  r.experiments.add(make_snapshot_closure_experiment());
  r.experiments.add(make_coarse_continuum_2d_experiment());  // the coarse continuum baseline
}

const Registry& builtin_registry() {
  static const Registry registry = [] {
    Registry r;
    register_builtin_strategies(r);
    register_builtin_experiments(r);
    return r;
  }();
  return registry;
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

}  // namespace closurelab
