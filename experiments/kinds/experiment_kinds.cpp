#include "core/base/errors.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/quadrature_convergence.hpp"
#include "experiments/kinds/reduced_model.hpp"
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
    k.push_back(make_snapshot_closure_experiment());
    return k;
  }();
  return kinds;
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
