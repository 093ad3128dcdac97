#pragma once
// The stress-quadrature strategy family (DESIGN.md §2): interaction stress on mesh nodes from particle
// velocities, exactly (2.13) or by the coarse quadrature (5.27). Filled in by the reduced-model issue.
#include <string>

namespace closurelab {

class StressQuadrature {
 public:
  virtual ~StressQuadrature() = default;
  virtual std::string name() const = 0;
};

}  // namespace closurelab
