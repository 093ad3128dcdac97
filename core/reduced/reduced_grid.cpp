#include "core/reduced/reduced_grid.hpp"

#include <cmath>

#include "core/base/errors.hpp"

namespace closurelab {

UniformMesh1D wall_to_wall_nodes(const Scene& scene, double target_spacing) {
  const double w = scene.wall_hi - scene.wall_lo;
  const int k = static_cast<int>(std::lround(w / target_spacing));
  if (k < 4)
    throw ConfigError("/solver/spacing_over_eta", "fewer than 4 coarse intervals across the channel (eta' too large)");
  return UniformMesh1D{scene.wall_lo, w / k, k + 1, false, 0.0};  // nodes on both walls (5.6)
}

ReducedGrid make_reduced_grid(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta,
                              bool staggered, bool walls_are_data) {
  if (!scene.x_invariant) throw ConfigError("/scene", "the coarse solver handles x-invariant scenes only");
  const double target = spacing_over_eta * kernel.eta();
  ReducedGrid g;
  g.periodic = !scene.has_walls;
  if (g.periodic) {
    const int k = static_cast<int>(std::lround(scene.box.ly / target));
    if (k < 4) throw ConfigError("/solver/spacing_over_eta", "fewer than 4 coarse nodes across the domain");
    g.coarse = UniformMesh1D::cell_centred(0.0, scene.box.ly, k, true);
    g.fine = UniformMesh1D::cell_centred(0.0, scene.box.ly, scene.ny, true);
    g.data = g.coarse;
    g.stress_axis = g.coarse;
    if (staggered) g.stress_axis.origin += 0.5 * g.coarse.spacing;
    return g;
  }
  g.coarse = wall_to_wall_nodes(scene, target);
  const double w = scene.wall_hi - scene.wall_lo;
  const int k = g.coarse.count - 1;
  // The deconvolution's data: the interior nodes. The wall nodes carry the imposed v̄ = 0 of (5.6), not an
  // average (the real average there is not zero: the window holds fluid), so they are not data; their
  // solution value is the particle velocity on the wall surface, zero by no slip. Used as data, the false
  // zero drives the reconstructed near-wall fluid backwards, the wall particles drag it forwards, and with
  // the wall constraint forces the loop diverges (measured for cc orders >= 1 and for cf).
  g.walls_are_data = walls_are_data;
  g.data = walls_are_data ? g.coarse : UniformMesh1D{scene.wall_lo + w / k, w / k, k - 1, false, 0.0};
  const int j_lo = static_cast<int>(std::floor(scene.wall_lo / scene.dx - 0.5)) + 1;
  int count = 0;
  while ((j_lo + count + 0.5) * scene.dx < scene.wall_hi) ++count;
  g.fine = UniformMesh1D{(j_lo + 0.5) * scene.dx, scene.dx, count, false, 0.0};
  g.stress_axis = g.coarse;
  if (staggered) g.stress_axis = UniformMesh1D{scene.wall_lo + 0.5 * g.coarse.spacing, g.coarse.spacing, k, false, 0.0};
  return g;
}

TensorMesh2D column_of(const Scene& scene, const UniformMesh1D& y_axis) {
  return TensorMesh2D{UniformMesh1D{0.0, scene.box.lx, 1, true, scene.box.lx}, y_axis};
}

}  // namespace closurelab
