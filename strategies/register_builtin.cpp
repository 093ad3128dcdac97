#include "strategies/register_builtin.hpp"

#include "core/averaging_kernel.hpp"
#include "core/deconvolver.hpp"
#include "core/scene.hpp"
#include "core/stress_quadrature.hpp"

namespace closurelab {

void register_builtin_strategies(Registry& r) {
  register_kernels(r);
  register_deconvolvers(r);
  register_quadratures(r);
  register_scenes(r);
}

const Registry& builtin_registry() {
  static const Registry registry = [] {
    Registry r;
    register_builtin_strategies(r);
    return r;
  }();
  return registry;
}

}  // namespace closurelab
