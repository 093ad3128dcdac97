#pragma once
// A particle row on a wall surface (core/scenes/wall_rows.cpp): refused, since whether it is wall or fluid would be
// decided by rounding.
#include <string>

namespace closurelab {

struct Scene;

// ConfigError at `eta_path` when a lattice row (j + 1/2) epsilon' lies within 1e-9 epsilon' of a wall surface
// y = wall_lo or y = wall_hi of `scene` (3 eta' / epsilon' a half-integer when the walls are 3 eta' thick): the
// engine holds a particle with y < wall_lo, the reduced models' meshes count rows from wall_lo / epsilon' - 1/2, and
// at equality the two decide by the last bit of different sums. The message names `eta_path` and `n_key` and the
// two nearest values of eta' / L (`length`: the L it is measured in) whose surface lies midway between two rows.
void check_rows_off_wall_surfaces(const Scene& scene, double length, const std::string& eta_path,
                                  const std::string& n_key);

}  // namespace closurelab
