#include "core/sph/equation_of_state.hpp"

#include <algorithm>

#include "core/base/errors.hpp"

namespace closurelab {

double VanDerWaalsEos::a_max(double phi) {
  const double d = 1.0 - phi;
  return std::min(1.0 / d, 1.0 / (2.0 * d * d));
}

VanDerWaalsEos VanDerWaalsEos::from_liquid(double n0, double mass, double sound_speed, double phi, double a,
                                           double k_star, const std::string& path) {
  if (!(phi > 0.0 && phi < 1.0))
    throw ConfigError(path + "/vdw_phi", "c_1 n0 must lie in (0, 1) (n0/c_1 is the close-packing density)");
  if (!(a >= 0.0 && a < a_max(phi)))
    throw ConfigError(path + "/vdw_a", "c_2 n0 / k_B T = " + std::to_string(a) + " must lie in [0, " +
                                           std::to_string(a_max(phi)) +
                                           "): above it P(n0) <= 0 (tensile instability) or dP/dn(n0) <= 0 "
                                           "(unstable liquid) for vdw_phi = " + std::to_string(phi));
  if (!(k_star >= 0.0 && k_star < 1.0))
    throw ConfigError(path + "/k_star", "the unlike-pair coefficient k* of (7.1) must lie in [0, 1) (k* < 1: the "
                                        "fluids do not mix; k* = 1 would make them one fluid)");
  VanDerWaalsEos e;
  const double d = 1.0 - phi;
  e.kt = mass * sound_speed * sound_speed / (1.0 / (d * d) - 2.0 * a);
  e.c1 = phi / n0;
  e.c2 = a * e.kt / n0;
  e.k_star = k_star;
  return e;
}

}  // namespace closurelab
