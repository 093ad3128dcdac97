#pragma once
// The regularizer C = LᵀL of Tikhonov's difference forms (4.7): L the first or second difference on the solution
// mesh (1D, or the Kronecker sum [I ⊗ L_x; L_y ⊗ I] on a tensor mesh; not periodic), or the first difference
// with the two end links to known zeros beyond a 1D solution mesh, each link weighted by the operator's
// link_weights (the viscous-dissipation prior of the near-wall closure).
#include <Eigen/SparseCore>

#include "core/closure/forward_operator.hpp"

namespace closurelab {

// order 0: C = I; 1, 2: first or second difference; 3: the zero-end, weighted first difference.
Eigen::SparseMatrix<double> regularizer_matrix(const ForwardOperator& a, int order);
// L itself (p x n; L = I for order 0), so that C = LᵀL: what the stacked QR and the standard-form
// transformation of Tikhonov's least-squares form use instead of C (they do not square L's condition number).
Eigen::SparseMatrix<double> regularizer_operator(const ForwardOperator& a, int order);

}  // namespace closurelab
