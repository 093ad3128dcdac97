#include "core/base/mesh.hpp"

#include <cmath>

#include "core/base/errors.hpp"

namespace closurelab {

Eigen::VectorXd UniformMesh1D::nodes() const {
  Eigen::VectorXd v(count);
  for (int i = 0; i < count; ++i) v[i] = node(i);
  return v;
}

UniformMesh1D UniformMesh1D::cell_centred(double start, double length, int count, bool periodic) {
  if (!(length > 0) || count < 1) throw ConfigError("", "mesh needs a positive length and at least one node");
  const double h = length / count;
  return UniformMesh1D{start + 0.5 * h, h, count, periodic, periodic ? length : 0.0};
}

UniformMesh1D UniformMesh1D::spanning(double lo, double hi, double spacing) {
  if (!(spacing > 0) || !(hi >= lo)) throw ConfigError("", "mesh needs a positive spacing and hi >= lo");
  const int n = static_cast<int>(std::floor((hi - lo) / spacing + 1e-9)) + 1;
  const double used = (n - 1) * spacing;
  return UniformMesh1D{lo + 0.5 * ((hi - lo) - used), spacing, n, false, 0.0};
}

}  // namespace closurelab
