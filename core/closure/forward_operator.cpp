#include "core/closure/forward_operator.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <unsupported/Eigen/KroneckerProduct>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"

namespace closurelab {


ForwardOperator ForwardOperator::from_dense(Eigen::MatrixXd a) {
  ForwardOperator op;
  op.storage_ = OperatorStorage::dense;
  op.rows_ = a.rows();
  op.cols_ = a.cols();
  op.dense_ = std::move(a);
  return op;
}
ForwardOperator ForwardOperator::from_sparse(Eigen::SparseMatrix<double> a) {
  ForwardOperator op;
  op.storage_ = OperatorStorage::sparse;
  op.rows_ = a.rows();
  op.cols_ = a.cols();
  a.makeCompressed();
  op.sparse_ = std::move(a);
  return op;
}
ForwardOperator ForwardOperator::from_kronecker(Eigen::MatrixXd a_y, Eigen::MatrixXd a_x) {
  ForwardOperator op;
  op.storage_ = OperatorStorage::kronecker;
  op.rows_ = a_x.rows() * a_y.rows();
  op.cols_ = a_x.cols() * a_y.cols();
  op.a_x_ = std::move(a_x);
  op.a_y_ = std::move(a_y);
  return op;
}

Eigen::VectorXd ForwardOperator::apply(const Eigen::VectorXd& x) const {
  if (x.size() != cols_)
    throw ConfigError("", "operator has " + std::to_string(cols_) + " columns but the vector has " +
                              std::to_string(x.size()) + " entries");
  switch (storage_) {
    case OperatorStorage::dense: return dense_ * x;
    case OperatorStorage::sparse: return sparse_ * x;
    case OperatorStorage::kronecker: {
      // (A_y ⊗ A_x) vec(X) = vec(A_x X A_yᵀ), X is cols(A_x) × cols(A_y) with x fastest.
      Eigen::Map<const Eigen::MatrixXd> X(x.data(), a_x_.cols(), a_y_.cols());
      Eigen::VectorXd y(rows_);
      Eigen::Map<Eigen::MatrixXd> Y(y.data(), a_x_.rows(), a_y_.rows());
      if (a_y_.size() == 1)
        Y.noalias() = a_y_(0, 0) * (a_x_ * X);
      else
        Y.noalias() = (a_x_ * X) * a_y_.transpose();
      return y;
    }
  }
  return {};
}

Eigen::VectorXd ForwardOperator::apply_transpose(const Eigen::VectorXd& y) const {
  if (y.size() != rows_)
    throw ConfigError("", "operator has " + std::to_string(rows_) + " rows but the vector has " +
                              std::to_string(y.size()) + " entries");
  switch (storage_) {
    case OperatorStorage::dense: return dense_.transpose() * y;
    case OperatorStorage::sparse: return sparse_.transpose() * y;
    case OperatorStorage::kronecker: {
      Eigen::Map<const Eigen::MatrixXd> Y(y.data(), a_x_.rows(), a_y_.rows());
      Eigen::VectorXd x(cols_);
      Eigen::Map<Eigen::MatrixXd> X(x.data(), a_x_.cols(), a_y_.cols());
      if (a_y_.size() == 1)
        X.noalias() = a_y_(0, 0) * (a_x_.transpose() * Y);
      else
        X.noalias() = (a_x_.transpose() * Y) * a_y_;
      return x;
    }
  }
  return {};
}

Eigen::MatrixXd ForwardOperator::to_dense() const {
  check_allocation(static_cast<double>(rows_) * static_cast<double>(cols_), sizeof(double),
                   "a dense copy of the " + std::to_string(rows_) + " x " + std::to_string(cols_) + " operator");
  switch (storage_) {
    case OperatorStorage::dense: return dense_;
    case OperatorStorage::sparse: return Eigen::MatrixXd(sparse_);
    case OperatorStorage::kronecker: return Eigen::kroneckerProduct(a_y_, a_x_).eval();
  }
  return {};
}

Eigen::SparseMatrix<double> ForwardOperator::to_sparse(double drop_tolerance) const {
  if (storage_ == OperatorStorage::sparse && drop_tolerance <= 0) return sparse_;
  Eigen::SparseMatrix<double> s;
  if (storage_ == OperatorStorage::kronecker) {
    // Prune each factor relative to its own maximum, then the product (entries <= tol·max|A|).
    const double mxx = a_x_.cwiseAbs().maxCoeff(), mxy = a_y_.cwiseAbs().maxCoeff();
    const double tol = drop_tolerance * mxx * mxy;
    Eigen::SparseMatrix<double> sx = a_x_.sparseView(1.0, 0.0), sy = a_y_.sparseView(1.0, 0.0);
    sx.prune([&](Eigen::Index, Eigen::Index, double v) { return std::abs(v) > drop_tolerance * mxx; });
    sy.prune([&](Eigen::Index, Eigen::Index, double v) { return std::abs(v) > drop_tolerance * mxy; });
    s = Eigen::kroneckerProduct(sy, sx).eval();
    s.prune([tol](Eigen::Index, Eigen::Index, double v) { return std::abs(v) > tol; });
  } else {
    const Eigen::MatrixXd d = to_dense();
    const double tol = drop_tolerance * d.cwiseAbs().maxCoeff();
    s = d.sparseView(1.0, 0.0);
    s.prune([tol](Eigen::Index, Eigen::Index, double v) { return std::abs(v) > tol; });
  }
  s.makeCompressed();
  return s;
}

bool ForwardOperator::is_symmetric(double tol) const {
  if (!is_square()) return false;
  switch (storage_) {
    case OperatorStorage::dense:
      return (dense_ - dense_.transpose()).cwiseAbs().maxCoeff() <= tol * dense_.cwiseAbs().maxCoeff();
    case OperatorStorage::sparse: {
      Eigen::SparseMatrix<double> d = sparse_ - Eigen::SparseMatrix<double>(sparse_.transpose());
      double m = 0.0, a = 0.0;
      for (int k = 0; k < d.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(d, k); it; ++it) m = std::max(m, std::abs(it.value()));
      for (int k = 0; k < sparse_.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(sparse_, k); it; ++it) a = std::max(a, std::abs(it.value()));
      return m <= tol * a;
    }
    case OperatorStorage::kronecker: {
      if (a_x_.rows() != a_x_.cols() || a_y_.rows() != a_y_.cols()) return false;
      auto sym = [tol](const Eigen::MatrixXd& f) {
        return (f - f.transpose()).cwiseAbs().maxCoeff() <= tol * f.cwiseAbs().maxCoeff();
      };
      return sym(a_x_) && sym(a_y_);
    }
  }
  return false;
}

double ForwardOperator::norm2_estimate() const {
  auto norm_dense = [](const Eigen::MatrixXd& m) {
    return m.size() == 0 ? 0.0 : Eigen::BDCSVD<Eigen::MatrixXd>(m).singularValues()(0);
  };
  switch (storage_) {
    case OperatorStorage::dense: return norm_dense(dense_);
    case OperatorStorage::kronecker: return norm_dense(a_x_) * norm_dense(a_y_);
    case OperatorStorage::sparse: {
      Eigen::VectorXd v = Eigen::VectorXd::Ones(cols_).normalized();
      double lambda = 0.0;
      for (int it = 0; it < 60; ++it) {
        Eigen::VectorXd w = sparse_.transpose() * (sparse_ * v);
        lambda = w.norm();
        if (lambda == 0) return 0.0;
        v = w / lambda;
      }
      return std::sqrt(lambda);
    }
  }
  return 0.0;
}

Eigen::MatrixXd kernel_matrix_1d(const AveragingKernel& kernel, const UniformMesh1D& data_mesh,
                                 const UniformMesh1D& solution_mesh) {
  if (data_mesh.periodic != solution_mesh.periodic ||
      (data_mesh.periodic && std::abs(data_mesh.period - solution_mesh.period) > 1e-12 * data_mesh.period))
    throw ConfigError("", "data and solution meshes must be both periodic with one period, or both not");
  const double h = solution_mesh.spacing;
  Eigen::MatrixXd a(data_mesh.count, solution_mesh.count);
  for (int j = 0; j < solution_mesh.count; ++j)
    for (int i = 0; i < data_mesh.count; ++i)
      a(i, j) = h * factor_over_images(kernel, data_mesh, data_mesh.node(i) - solution_mesh.node(j));
  return a;
}

namespace {
std::pair<const UniformMesh1D*, const UniformMesh1D*> pick(const UniformMesh1D& coarse, const UniformMesh1D& fine,
                                                           Discretization d) {
  switch (d) {
    case Discretization::coarse_coarse: return {&coarse, &coarse};
    case Discretization::coarse_fine: return {&coarse, &fine};
    case Discretization::fine_fine: return {&fine, &fine};
  }
  return {&coarse, &coarse};
}

ForwardOperator store(Eigen::MatrixXd a_y, Eigen::MatrixXd a_x, OperatorStorage storage, double drop) {
  ForwardOperator k = ForwardOperator::from_kronecker(std::move(a_y), std::move(a_x));
  switch (storage) {
    case OperatorStorage::kronecker: return k;
    case OperatorStorage::dense: return ForwardOperator::from_dense(k.to_dense());
    case OperatorStorage::sparse: return ForwardOperator::from_sparse(k.to_sparse(drop));
  }
  return k;
}
}  // namespace

ForwardOperator make_averaging_operator_2d(const AveragingKernel& kernel, const TensorMesh2D& coarse,
                                           const TensorMesh2D& fine, Discretization disc, OperatorStorage storage,
                                           double drop_tolerance) {
  auto [dx, sx] = pick(coarse.x, fine.x, disc);
  auto [dy, sy] = pick(coarse.y, fine.y, disc);
  ForwardOperator op = store(kernel_matrix_1d(kernel, *dy, *sy), kernel_matrix_1d(kernel, *dx, *sx), storage,
                             drop_tolerance);
  op.data_mesh = TensorMesh2D{*dx, *dy};
  op.solution_mesh = TensorMesh2D{*sx, *sy};
  op.dimension = 2;
  return op;
}

ForwardOperator make_averaging_operator_1d(const AveragingKernel& kernel, const UniformMesh1D& coarse,
                                           const UniformMesh1D& fine, Discretization disc, OperatorStorage storage,
                                           double drop_tolerance) {
  auto [d, s] = pick(coarse, fine, disc);
  ForwardOperator op =
      store(Eigen::MatrixXd::Identity(1, 1), kernel_matrix_1d(kernel, *d, *s), storage, drop_tolerance);
  const UniformMesh1D single{0.0, 1.0, 1, false, 0.0};
  op.data_mesh = TensorMesh2D{*d, single};
  op.solution_mesh = TensorMesh2D{*s, single};
  op.dimension = 1;
  return op;
}

}  // namespace closurelab
