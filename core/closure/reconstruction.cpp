#include "core/closure/reconstruction.hpp"

#include <cmath>
#include <stdexcept>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"

namespace closurelab {

namespace {
// Left node index and weight of the right node for coordinate t on axis m.
void locate(const UniformMesh1D& m, double t, int& i0, int& i1, double& w) {
  double s = (t - m.origin) / m.spacing;
  if (m.periodic) {
    const double n = m.count;
    s = std::fmod(s, n);
    if (s < 0) s += n;
    i0 = static_cast<int>(std::floor(s));
    w = s - i0;
    i0 %= m.count;
    i1 = (i0 + 1) % m.count;
    return;
  }
  if (m.count == 1 || s <= 0) {
    i0 = i1 = 0;
    w = 0;
    return;
  }
  if (s >= m.count - 1) {
    i0 = i1 = m.count - 1;
    w = 0;
    return;
  }
  i0 = static_cast<int>(std::floor(s));
  i1 = i0 + 1;
  w = s - i0;
}

}  // namespace

Reconstruction::Reconstruction(TensorMesh2D mesh, int dimension, Eigen::VectorXd values)
    : mesh_(std::move(mesh)), dimension_(dimension), values_(std::move(values)) {
  const Eigen::Index expected = dimension_ == 1 ? mesh_.nx() : mesh_.size();
  if (values_.size() != expected)
    throw ConfigError("", "reconstruction has " + std::to_string(values_.size()) + " values for a mesh of " +
                              std::to_string(expected) + " nodes");
}

double Reconstruction::sample(const Vec2& p) const {
  int i0, i1;
  double wx;
  locate(mesh_.x, p.x(), i0, i1, wx);
  if (dimension_ == 1) return (1 - wx) * values_(i0) + wx * values_(i1);
  int j0, j1;
  double wy;
  locate(mesh_.y, p.y(), j0, j1, wy);
  const int nx = mesh_.nx();
  return (1 - wy) * ((1 - wx) * values_(j0 * nx + i0) + wx * values_(j0 * nx + i1)) +
         wy * ((1 - wx) * values_(j1 * nx + i0) + wx * values_(j1 * nx + i1));
}

Eigen::VectorXd Reconstruction::sample(const std::vector<Vec2>& points) const {
  Eigen::VectorXd v(static_cast<Eigen::Index>(points.size()));
  for (size_t q = 0; q < points.size(); ++q) v(static_cast<Eigen::Index>(q)) = sample(points[q]);
  return v;
}

Eigen::Matrix2Xd sample_pair(const Reconstruction& x, const Reconstruction& y, const std::vector<Vec2>& points) {
  const TensorMesh2D& m = x.mesh();
  if (y.values().size() != x.values().size()) throw std::invalid_argument("sample_pair: the two fields differ in size");
  const Eigen::VectorXd &a = x.values(), &b = y.values();
  const int nx = m.nx();
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(points.size()));
  for (size_t q = 0; q < points.size(); ++q) {
    int i0, i1, j0, j1;
    double wx, wy;
    locate(m.x, points[q].x(), i0, i1, wx);
    locate(m.y, points[q].y(), j0, j1, wy);
    const int p00 = j0 * nx + i0, p01 = j0 * nx + i1, p10 = j1 * nx + i0, p11 = j1 * nx + i1;
    const auto Eq = static_cast<Eigen::Index>(q);
    out(0, Eq) = (1 - wy) * ((1 - wx) * a(p00) + wx * a(p01)) + wy * ((1 - wx) * a(p10) + wx * a(p11));
    out(1, Eq) = (1 - wy) * ((1 - wx) * b(p00) + wx * b(p01)) + wy * ((1 - wx) * b(p10) + wx * b(p11));
  }
  return out;
}

Reconstruction reconstruction_of(const ForwardOperator& a, Eigen::VectorXd x) {
  if (!a.solution_mesh || a.dimension == 0)
    throw ConfigError("", "the operator carries no solution mesh (built from a matrix, not from a kernel and meshes)");
  return Reconstruction(*a.solution_mesh, a.dimension, std::move(x));
}

Eigen::VectorXd coarse_fine_quadrature(const AveragingKernel& kernel, const TensorMesh2D& coarse, int dimension,
                                       const Eigen::VectorXd& u, const std::vector<Vec2>& points) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(points.size()));
  const int nx = coarse.nx(), ny = dimension == 1 ? 1 : coarse.ny();
  Eigen::VectorXd fx(nx), fy(ny);
  for (size_t q = 0; q < points.size(); ++q) {
    for (int i = 0; i < nx; ++i)
      fx(i) = coarse.x.spacing * factor_over_images(kernel, coarse.x, points[q].x() - coarse.x.node(i));
    if (dimension == 1) {
      out(static_cast<Eigen::Index>(q)) = fx.dot(u);
      continue;
    }
    for (int j = 0; j < ny; ++j)
      fy(j) = coarse.y.spacing * factor_over_images(kernel, coarse.y, points[q].y() - coarse.y.node(j));
    Eigen::Map<const Eigen::MatrixXd> U(u.data(), nx, ny);
    out(static_cast<Eigen::Index>(q)) = fx.dot(U * fy);
  }
  return out;
}

Eigen::VectorXd landweber_series_at_points(const AveragingKernel& kernel, const TensorMesh2D& coarse, int dimension,
                                           const Eigen::VectorXd& b, int order, const std::vector<Vec2>& points) {
  const ForwardOperator a = dimension == 1
                                ? make_averaging_operator_1d(kernel, coarse.x, coarse.x, Discretization::coarse_coarse)
                                : make_averaging_operator_2d(kernel, coarse, coarse, Discretization::coarse_coarse);
  // x_n(y) = L[b](y) + Σ_{k=1}^{n} ( L[u_{k−1}](y) − Q[u_{k−1}](y) ),  u_k = (I − A) u_{k−1}, u_0 = b.
  Eigen::VectorXd u = b;
  Eigen::VectorXd out = Reconstruction(coarse, dimension, b).sample(points);
  for (int k = 1; k <= order; ++k) {
    out += Reconstruction(coarse, dimension, u).sample(points) -
           coarse_fine_quadrature(kernel, coarse, dimension, u, points);
    u -= a.apply(u);
  }
  return out;
}

}  // namespace closurelab
