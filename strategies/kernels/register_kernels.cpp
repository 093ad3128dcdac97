#include "core/base/registry.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"
#include "strategies/register_builtin.hpp"

namespace closurelab {

void register_kernels(Registry& r) {
  r.kernels.add({"gaussian", "Gaussian window (2.7), psi = exp(-|x|^2/eta^2)/(pi eta^2)",
                 {number_param("eta", nullptr, "window length eta' (model units)", 0.0, {}, true)}},
                [](const json& p) { return std::make_unique<GaussianKernel>(p.at("eta").get<double>()); });
  r.kernels.add({"cutoff_gaussian", "Gaussian truncated to the box |x|,|y| <= cutoff*eta and renormalized",
                 {number_param("eta", nullptr, "window length eta' (model units)", 0.0, {}, true),
                  number_param("cutoff", 3.0, "truncation radius in units of eta", 0.5, 20.0)}},
                [](const json& p) {
                  return std::make_unique<CutoffGaussianKernel>(p.at("eta").get<double>(), p.at("cutoff").get<double>());
                });
}

}  // namespace closurelab
