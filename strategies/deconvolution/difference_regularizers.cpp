#include "strategies/deconvolution/difference_regularizers.hpp"

#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/KroneckerProduct>
#include <vector>

namespace closurelab {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

SpMat difference_1d(int n, int order) {
  SpMat d(std::max(n - order, 0), n);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i + order < n; ++i) {
    if (order == 1) {
      t.emplace_back(i, i, -1.0);
      t.emplace_back(i, i + 1, 1.0);
    } else {
      t.emplace_back(i, i, 1.0);
      t.emplace_back(i, i + 1, -2.0);
      t.emplace_back(i, i + 2, 1.0);
    }
  }
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

// The first difference with the two end links to known zeros beyond the solution mesh ((n + 1) x n), each
// link weighted by √w (w from the operator's link_weights, else 1): ‖Lx‖² = Σ_links w (x_{a+1} − x_a)², the
// discrete (viscous) Dirichlet energy. 1D solution meshes only, or an operator that carries its own links
// (ForwardOperator::difference_links).
SpMat zero_end_difference(const ForwardOperator& a) {
  const int n = static_cast<int>(a.cols());
  if (a.difference_links) {
    if (a.difference_links->cols() != n || a.difference_links->rows() == 0)
      throw ConfigError("/regularizer", "the operator's difference links must have one column per unknown");
    return *a.difference_links;
  }
  if (a.dimension == 2) throw ConfigError("/regularizer", "first_difference_zero_ends needs a 1D solution mesh");
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n + 1);
  if (a.link_weights) {
    if (a.link_weights->size() != n + 1 || (a.link_weights->array() <= 0).any() || !a.link_weights->allFinite())
      throw ConfigError("/regularizer", "the operator's link weights must be n + 1 positive numbers");
    w = *a.link_weights;
  }
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i <= n; ++i) {
    const double s = std::sqrt(w[i]);
    if (i < n) t.emplace_back(i, i, s);
    if (i > 0) t.emplace_back(i, i - 1, -s);
  }
  SpMat l(n + 1, n);
  l.setFromTriplets(t.begin(), t.end());
  return l;
}

}  // namespace

// L itself (L = I for the identity; order 3: the zero-end, weighted first difference above).
SpMat regularizer_operator(const ForwardOperator& a, int order) {
  const int n = static_cast<int>(a.cols());
  SpMat identity(n, n);
  identity.setIdentity();
  if (order == 0) return identity;
  if (order == 3) return zero_end_difference(a);
  int nx = n, ny = 1;
  if (a.dimension == 2 && a.solution_mesh) {
    nx = a.solution_mesh->nx();
    ny = a.solution_mesh->ny();
  }
  SpMat l;
  if (ny == 1) {
    l = difference_1d(nx, order);
  } else {
    SpMat ix(nx, nx), iy(ny, ny);
    ix.setIdentity();
    iy.setIdentity();
    const SpMat lx = Eigen::kroneckerProduct(iy, difference_1d(nx, order)).eval();
    const SpMat ly = Eigen::kroneckerProduct(difference_1d(ny, order), ix).eval();
    l.resize(lx.rows() + ly.rows(), n);
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < lx.outerSize(); ++k)
      for (SpMat::InnerIterator it(lx, k); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
    for (int k = 0; k < ly.outerSize(); ++k)
      for (SpMat::InnerIterator it(ly, k); it; ++it) t.emplace_back(lx.rows() + it.row(), it.col(), it.value());
    l.setFromTriplets(t.begin(), t.end());
  }
  return l;
}

// C = LᵀL (C = I for the identity).
SpMat regularizer_matrix(const ForwardOperator& a, int order) {
  if (order == 0) return regularizer_operator(a, 0);
  const SpMat l = regularizer_operator(a, order);
  return SpMat(l.transpose() * l);
}

}  // namespace closurelab
