#include "core/closure/stress_quadrature.hpp"

namespace closurelab {

json QuadratureCost::to_json() const {
  return {{"evaluations", evaluations},   {"pair_forces", pair_forces},           {"bond_weights", bond_weights},
          {"sample_points", sample_points}, {"setup_seconds", setup_seconds}, {"evaluate_seconds", evaluate_seconds}};
}

}  // namespace closurelab
