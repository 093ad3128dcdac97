#pragma once
// Uniform meshes: a 1D axis of equally spaced nodes (optionally periodic with a period), and the 2D
// tensor-product mesh built from two axes. Node (i, j) of a TensorMesh2D has flat index j * nx + i
// (x fastest), matching the Kronecker ordering A = A_y ⊗ A_x.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace closurelab {

using Vec2 = Eigen::Vector2d;

struct UniformMesh1D {
  double origin = 0.0;   // position of node 0
  double spacing = 1.0;  // > 0
  int count = 1;         // >= 1
  bool periodic = false;
  double period = 0.0;   // the periodic length (only meaningful when periodic)

  double node(int i) const { return origin + spacing * i; }
  Eigen::VectorXd nodes() const;

  // Cell-centred nodes (k + 1/2) * length / count, k = 0..count-1, on [start, start + length).
  static UniformMesh1D cell_centred(double start, double length, int count, bool periodic);
  // Nodes with a given spacing inside [lo, hi], symmetric about the interval's middle.
  static UniformMesh1D spanning(double lo, double hi, double spacing);
};

// Calls f(node index, node − image of q) for every node of `axis` within `radius` of the point q, summing
// over the periodic images of q when the axis is periodic (a node may then be visited more than once).
template <class F>
void for_nodes_within(const UniformMesh1D& axis, double q, double radius, F f) {
  const auto visit = [&](double qi) {
    const int lo = std::max(0, static_cast<int>(std::ceil((qi - radius - axis.origin) / axis.spacing)));
    const int hi = std::min(axis.count - 1, static_cast<int>(std::floor((qi + radius - axis.origin) / axis.spacing)));
    for (int i = lo; i <= hi; ++i) f(i, axis.node(i) - qi);
  };
  if (!axis.periodic) return visit(q);
  const double last = axis.node(axis.count - 1);
  const int kmin = static_cast<int>(std::floor((axis.origin - radius - q) / axis.period));
  const int kmax = static_cast<int>(std::ceil((last + radius - q) / axis.period));
  for (int k = kmin; k <= kmax; ++k) visit(q + k * axis.period);
}

struct TensorMesh2D {
  UniformMesh1D x, y;

  int nx() const { return x.count; }
  int ny() const { return y.count; }
  int size() const { return x.count * y.count; }
  int index(int i, int j) const { return j * x.count + i; }
  Vec2 node(int i, int j) const { return {x.node(i), y.node(j)}; }
  Vec2 node(int flat) const { return node(flat % x.count, flat / x.count); }
  double cell_area() const { return x.spacing * y.spacing; }
};

}  // namespace closurelab
