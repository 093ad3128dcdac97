#include "core/closure/stress_quadrature.hpp"

namespace closurelab {

json QuadratureCost::to_json() const {
  return {{"evaluations", evaluations},   {"pair_forces", pair_forces},           {"bond_weights", bond_weights},
          {"sample_points", sample_points}, {"setup_seconds", setup_seconds}, {"evaluate_seconds", evaluate_seconds}};
}

QuadratureResult finite_or_issue(QuadratureResult r, const std::string& who) {
  for (const auto& [component, field] : r.stress)
    if (!field.allFinite()) {
      r.status = Status::numerical_issue;
      r.message = who + ": non-finite interaction stress T_" + component;
      break;
    }
  return r;
}

}  // namespace closurelab
