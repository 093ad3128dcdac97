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
    k.push_back(make_reduced_model_experiment());
    k.push_back(make_reduced_model_2d_experiment());
    k.push_back(make_snapshot_closure_experiment());
    return k;
  }();
  return kinds;
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

const ExperimentKind& find_experiment_kind(const std::string& name, const std::string& path) {
  std::string known;
  for (const auto& k : experiment_kinds()) {
    if (k->name() == name) return *k;
    known += (known.empty() ? "" : ", ") + k->name();
  }
  throw ConfigError(path, "unknown experiment kind '" + name + "'; known: " + known);
}

}  // namespace closurelab
