#include "strategies/register_builtin.hpp"

#include "core/averaging/averaging_kernel.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/sph/scene.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/reduced/integrator.hpp"

namespace closurelab {

void register_builtin_strategies(Registry& r) {
  if (r.kernels.contains("gaussian")) return;  // already registered
  register_kernels(r);
  register_deconvolvers(r);
  register_quadratures(r);
  register_scenes(r);
  register_integrators(r);
}

}  // namespace closurelab
