#pragma once
// Forward operators A for the averaging R_η (4.1), discretized as in §4.2: the data b live on a "data" mesh,
// the solution x on a "solution" mesh, and A_ij = w_j ψ_η(x_i − y_j) with w_j the solution mesh's cell size
// (a quadrature of (4.1)). Three discretizations:
//   coarse_coarse  data and solution on the coarse (meso) mesh;
//   coarse_fine    data on the coarse mesh, solution on the fine mesh (rectangular A);
//   fine_fine      both on the fine mesh.
// On a tensor mesh the separable window ψ(x, y) = φ(x)φ(y) gives A = A_y ⊗ A_x (flat index j*nx + i); the
// operator keeps that structure and applies it as A_x X A_yᵀ without forming the Kronecker product.
// Operators can also be plain dense or sparse matrices (user systems, cut-off kernels, classic test problems).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <string>

#include "core/base/enum_names.hpp"
#include "core/base/mesh.hpp"

namespace closurelab {

class AveragingKernel;

enum class Discretization { coarse_coarse, coarse_fine, fine_fine };
template <>
struct EnumNames<Discretization> {
  static constexpr std::array<std::pair<Discretization, std::string_view>, 3> table{
      {{Discretization::coarse_coarse, "coarse_coarse"},
       {Discretization::coarse_fine, "coarse_fine"},
       {Discretization::fine_fine, "fine_fine"}}};
};
inline Discretization parse_discretization(const std::string& s, const std::string& path) {
  return parse_name<Discretization>(s, path);
}
inline std::string to_string(Discretization d) { return name_of(d); }

enum class OperatorStorage { dense, sparse, kronecker };
template <>
struct EnumNames<OperatorStorage> {
  static constexpr std::array<std::pair<OperatorStorage, std::string_view>, 3> table{
      {{OperatorStorage::dense, "dense"}, {OperatorStorage::sparse, "sparse"}, {OperatorStorage::kronecker, "kronecker"}}};
};
inline OperatorStorage parse_operator_storage(const std::string& s, const std::string& path) {
  return parse_name<OperatorStorage>(s, path);
}
inline std::string to_string(OperatorStorage s) { return name_of(s); }

class ForwardOperator {
 public:
  static ForwardOperator from_dense(Eigen::MatrixXd a);
  static ForwardOperator from_sparse(Eigen::SparseMatrix<double> a);
  // A = A_y ⊗ A_x; a 1D operator is from_kronecker(identity(1), A_x).
  static ForwardOperator from_kronecker(Eigen::MatrixXd a_y, Eigen::MatrixXd a_x);

  OperatorStorage storage() const { return storage_; }
  Eigen::Index rows() const { return rows_; }
  Eigen::Index cols() const { return cols_; }
  bool is_square() const { return rows_ == cols_; }

  Eigen::VectorXd apply(const Eigen::VectorXd& x) const;            // A x
  Eigen::VectorXd apply_transpose(const Eigen::VectorXd& y) const;  // Aᵀ y

  const Eigen::MatrixXd& dense() const { return dense_; }           // storage dense only
  const Eigen::SparseMatrix<double>& sparse() const { return sparse_; }  // storage sparse only
  const Eigen::MatrixXd& factor_x() const { return a_x_; }          // storage kronecker only
  const Eigen::MatrixXd& factor_y() const { return a_y_; }

  Eigen::MatrixXd to_dense() const;
  // Entries with |a_ij| <= drop_tolerance * max|a| are dropped.
  Eigen::SparseMatrix<double> to_sparse(double drop_tolerance = 0.0) const;
  // Symmetry check ‖A − Aᵀ‖_max <= tol ‖A‖_max (false when not square).
  bool is_symmetric(double tol = 1e-12) const;
  // ‖A‖₂: exact for Kronecker (‖A_x‖‖A_y‖) and dense; by 60 power iterations on AᵀA for sparse.
  double norm2_estimate() const;

  // The meshes, when the operator was built from a kernel (used by Reconstruction and difference operators).
  std::optional<TensorMesh2D> data_mesh, solution_mesh;
  int dimension = 0;  // 1 or 2 when built from meshes, 0 otherwise
  // 1D solution meshes whose values beyond both ends are known zeros (a channel's wall rows): optional weights
  // of the n + 1 links, the two end links to the known zeros included (e.g. the viscosity at each link, for
  // a minimum-viscous-dissipation prior); used by difference regularizers that include the end links.
  std::optional<Eigen::VectorXd> link_weights;
  // Unknowns that are not a tensor mesh (e.g. the reconstruction nodes outside a solid, core/reduced/force_density_2d):
  // the weighted first difference L over their links, one row per link, √w (x_p − x_q), a link to a known zero with
  // its one entry (cols() columns). first_difference_zero_ends uses it in place of the 1D construction.
  std::optional<Eigen::SparseMatrix<double>> difference_links;

 private:
  OperatorStorage storage_ = OperatorStorage::dense;
  Eigen::Index rows_ = 0, cols_ = 0;
  Eigen::MatrixXd dense_, a_x_, a_y_;
  Eigen::SparseMatrix<double> sparse_;
};

// The 1D factor: A_ij = h_sol φ(x_i − y_j), x_i data nodes, y_j solution nodes; periodic meshes sum the
// periodic images (both meshes must then share the period).
Eigen::MatrixXd kernel_matrix_1d(const AveragingKernel& kernel, const UniformMesh1D& data_mesh,
                                 const UniformMesh1D& solution_mesh);

// R_η on a tensor mesh (2D) at the named discretization. `storage` kronecker keeps A = A_y ⊗ A_x; dense
// forms the product; sparse drops entries below drop_tolerance·max (the cut-off of the kernel's support).
ForwardOperator make_averaging_operator_2d(const AveragingKernel& kernel, const TensorMesh2D& coarse,
                                           const TensorMesh2D& fine, Discretization disc,
                                           OperatorStorage storage = OperatorStorage::kronecker,
                                           double drop_tolerance = 1e-16);
// The same on a line (the y factor is the 1×1 identity).
ForwardOperator make_averaging_operator_1d(const AveragingKernel& kernel, const UniformMesh1D& coarse,
                                           const UniformMesh1D& fine, Discretization disc,
                                           OperatorStorage storage = OperatorStorage::kronecker,
                                           double drop_tolerance = 1e-16);

}  // namespace closurelab
