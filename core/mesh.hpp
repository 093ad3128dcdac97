#pragma once
// Uniform meshes: a 1D axis of equally spaced nodes (optionally periodic with a period), and the 2D
// tensor-product mesh built from two axes. Node (i, j) of a TensorMesh2D has flat index j * nx + i
// (x fastest), matching the Kronecker ordering A = A_y ⊗ A_x.
#include <Eigen/Core>
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
