#include "core/closure/stress_quadrature.hpp"
#include "strategies/quadrature/coarse_quadrature.hpp"
#include "strategies/quadrature/exact_quadrature.hpp"
#include "strategies/register_builtin.hpp"

namespace closurelab {

void register_quadratures(Registry& r) {
  r.quadratures.add({"exact", "pair sum (2.13) over every interacting particle pair, bond weights tabulated once; O(N)", {}},
                    [](const json&) { return std::make_unique<ExactQuadrature>(); });
  r.quadratures.add(
      {"coarse",
       "coarse quadrature (5.27): R on a lattice-anchored grid of strides (stride_x, stride_y), rho over the SPH "
       "support's lattice offsets; N/N_C = stride_x*stride_y (paper: 16 = 4x4, 32 = 4x8, 64 = 8x8 on 192^2), or "
       "n_x*stride_y with stride_x = 0; cost independent of N",
       {integer_param("stride_y", 4, "R-grid spacing along y in lattice spacings; must divide n_y", 1, {}),
        integer_param("stride_x", 0,
                      "R-grid spacing along x in lattice spacings, dividing n_x; 0: one R column per strip period "
                      "with the bond weight integrated exactly in x (x-invariant scenes only)",
                      0, {}),
        string_param("wall_band", "coarse",
                     "coarse: plain (5.27), R-rows of stride_y everywhere (the paper); fine: R-rows within one SPH "
                     "support of a wall surface at lattice resolution (resolves the jump of the integrand there)",
                     {"coarse", "fine"})}},
      [](const json& p) {
        return std::make_unique<CoarseQuadrature>(p.at("stride_x").get<int>(), p.at("stride_y").get<int>(),
                                                  p.at("wall_band") == "fine");
      });
}

}  // namespace closurelab
