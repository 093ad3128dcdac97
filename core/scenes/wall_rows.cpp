#include "core/scenes/wall_rows.hpp"

#include <cmath>
#include <cstdio>

#include "core/base/errors.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

void check_rows_off_wall_surfaces(const Scene& s, double length, const std::string& eta_path, const std::string& n_key) {
  if (!s.has_walls) return;
  for (const double surface : {s.wall_lo, s.wall_hi}) {
    const double rows = surface / s.dx - 0.5;  // the row index the surface would be, were it on one
    if (std::abs(rows - std::nearbyint(rows)) > 1e-9) continue;
    // The walls are 3 eta' thick: 3 eta' / epsilon' = r; an integer r puts the surface midway between two rows.
    const double r = 3.0 * s.eta / s.dx;
    const double below = std::floor(r) * s.dx / (3.0 * length), above = std::ceil(r + 1e-9) * s.dx / (3.0 * length);
    char msg[640];
    std::snprintf(msg, sizeof msg,
                  "a particle row lies on the wall surface y = %.10g (3 eta'/epsilon' = %.10g with %s = %d): whether "
                  "it is wall or fluid would be decided by rounding, and the direct run and the reduced model need "
                  "not decide alike (a 9.9 %% error reported ok); take %s = %.10g or %.10g (3 eta'/epsilon' an "
                  "integer: the surface midway between two rows), or another %s",
                  surface, r, n_key.c_str(), s.ny, eta_path.substr(eta_path.rfind('/') + 1).c_str(), below, above,
                  n_key.c_str());
    throw ConfigError(eta_path, msg);
  }
}

}  // namespace closurelab
