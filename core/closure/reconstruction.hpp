#pragma once
// A deconvolved field that can be sampled anywhere (§4.2): values on the solution mesh, evaluated between
// nodes by (bi)linear interpolation (periodic axes wrap, others clamp to the end nodes).
//
// For the paper's coarse–fine interpolation of the Landweber series (4.9) there is a second evaluation:
// x_n = b + Σ_{k=1}^{n} (I − A)^k b is rendered at fine points y by interpolating b linearly and replacing A by
// the coarse–fine quadrature of the kernel, (A u)(y) = H Σ_i ψ_η(y − x_i) u_i over the coarse nodes x_i (the
// paper's formula for (Ab)_j; the weight is the coarse cell size H, which makes it a quadrature of (4.1)).
#include <Eigen/Core>
#include <vector>

#include "core/base/mesh.hpp"

namespace closurelab {

class AveragingKernel;

class Reconstruction {
 public:
  // `dimension` 1: values on mesh.x only (mesh.y ignored); 2: values on the tensor mesh (flat j*nx + i).
  Reconstruction(TensorMesh2D mesh, int dimension, Eigen::VectorXd values);
  const Eigen::VectorXd& values() const { return values_; }
  const TensorMesh2D& mesh() const { return mesh_; }
  double sample(const Vec2& point) const;
  Eigen::VectorXd sample(const std::vector<Vec2>& points) const;

 private:
  TensorMesh2D mesh_;
  int dimension_;
  Eigen::VectorXd values_;
};

// Two fields on one 2D mesh (a velocity's components) sampled at the same points, each point located once: row 0
// `x`'s values, row 1 `y`'s, each equal to its own sample(points) to the bit.
Eigen::Matrix2Xd sample_pair(const Reconstruction& x, const Reconstruction& y, const std::vector<Vec2>& points);

class ForwardOperator;
// The field of a solution x of A x = b on A's solution mesh (A built by make_averaging_operator_1d/2d);
// ConfigError when A carries no mesh (e.g. a user matrix).
Reconstruction reconstruction_of(const ForwardOperator& a, Eigen::VectorXd x);

// The coarse–fine quadrature of the kernel, (A u)(y) = H Σ_i ψ_η(y − x_i) u_i, at arbitrary points
// (1D: ψ → φ and only x is used). Periodic axes sum the images.
Eigen::VectorXd coarse_fine_quadrature(const AveragingKernel& kernel, const TensorMesh2D& coarse, int dimension,
                                       const Eigen::VectorXd& u, const std::vector<Vec2>& points);

// The Landweber series of order n computed on the coarse mesh with the coarse–coarse operator A_cc and
// rendered at `points` as described above (§4.2).
Eigen::VectorXd landweber_series_at_points(const AveragingKernel& kernel, const TensorMesh2D& coarse, int dimension,
                                           const Eigen::VectorXd& b, int order, const std::vector<Vec2>& points);

}  // namespace closurelab
