// Recovery on known fields: noise-free data of a well-posed coarse–coarse Gaussian operator are recovered to
// <= 1e-8 by every strategy, and the Kronecker, dense and sparse paths of one method agree.
#include <gtest/gtest.h>

#include <cmath>

#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/base/registry.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {
Eigen::VectorXd field(const TensorMesh2D& m, int dim) {
  const int n = dim == 1 ? m.nx() : m.size();
  Eigen::VectorXd v(n);
  for (int f = 0; f < n; ++f) {
    const Vec2 p = dim == 1 ? Vec2(m.x.node(f), 0.0) : m.node(f);
    v(f) = std::exp(-std::pow((p.x() - 0.4) / 0.12, 2)) + 0.5 * std::sin(3 * p.x() + 2 * p.y()) * (dim == 2 ? 1.0 : 0.0);
  }
  return v;
}
DeconvolutionResult solve(const json& config, const ForwardOperator& a, const Eigen::VectorXd& b) {
  auto d = builtin_registry().deconvolvers.create(config, "/m");
  d->setup(a);
  return d->solve(b);
}
}  // namespace

TEST(DeconvRecovery, NoiseFreeWellPosedCoarseCoarseGaussianIsRecoveredTo1e8) {
  // η = h: κ(A) ≈ 6 on 40 nodes, so every convergent method reaches the data's rounding level.
  const UniformMesh1D m = UniformMesh1D::cell_centred(0, 1, 40, false);
  const GaussianKernel k(m.spacing);
  const ForwardOperator a = make_averaging_operator_1d(k, m, m, Discretization::coarse_coarse);
  const Eigen::VectorXd x = field(TensorMesh2D{m, UniformMesh1D{}}, 1), b = a.apply(x);
  const std::vector<json> configs = {
      {{"name", "landweber"}, {"order", 400}},
      {{"name", "landweber_relaxed"}, {"iterations", 4000}},
      {{"name", "tikhonov"}, {"alpha", 1e-15}},
      {{"name", "tikhonov"}, {"alpha", 1e-15}, {"form", "paper"}},
      {{"name", "tikhonov"}, {"alpha", 1e-15}, {"backend", "dense"}},
      {{"name", "tikhonov"}, {"alpha", 1e-13}, {"backend", "sparse"}},
      {{"name", "tikhonov"}, {"alpha", 1e-14}, {"regularizer", "second_difference"}},
      {{"name", "tsvd"}, {"k", 40}},
      {{"name", "tsvd"}, {"truncation", "threshold"}, {"threshold", 1e-6}},
      {{"name", "cg"}, {"iterations", 200}},
      {{"name", "cgls"}, {"iterations", 200}}};
  for (const auto& c : configs) {
    const DeconvolutionResult r = solve(c, a, b);
    EXPECT_LE((r.x - x).norm(), 1e-8 * x.norm()) << c.dump() << " " << r.stats.message;
    EXPECT_NE(r.status, DeconvolutionStatus::numerical_issue) << c.dump();
  }
}

TEST(DeconvRecovery, KroneckerDenseAndSparsePathsAgreeIn2D) {
  const TensorMesh2D m{UniformMesh1D::cell_centred(0, 1, 14, false), UniformMesh1D::cell_centred(0, 0.6, 9, false)};
  const GaussianKernel k(1.2 * m.x.spacing);
  const ForwardOperator kr = make_averaging_operator_2d(k, m, m, Discretization::coarse_coarse, OperatorStorage::kronecker);
  const ForwardOperator de = make_averaging_operator_2d(k, m, m, Discretization::coarse_coarse, OperatorStorage::dense);
  const ForwardOperator sp = make_averaging_operator_2d(k, m, m, Discretization::coarse_coarse, OperatorStorage::sparse);
  const Eigen::VectorXd x = field(m, 2), b = kr.apply(x);
  for (const json& c : {json{{"name", "tikhonov"}, {"alpha", 1e-6}}, json{{"name", "tikhonov"}, {"alpha", 1e-4}, {"form", "paper"}},
                        json{{"name", "tsvd"}, {"k", 60}}}) {
    const Eigen::VectorXd xk = solve(c, kr, b).x, xd = solve(c, de, b).x;
    EXPECT_LE((xk - xd).norm(), 1e-9 * xd.norm()) << c.dump();
  }
  // Tikhonov with C = I: spectral (Kronecker SVD), dense Cholesky and CHOLMOD give one solution.
  json t = {{"name", "tikhonov"}, {"alpha", 1e-6}};
  const Eigen::VectorXd spectral = solve(t, kr, b).x;
  t["backend"] = "dense";
  const Eigen::VectorXd dense = solve(t, de, b).x;
  t["backend"] = "sparse";
  const Eigen::VectorXd cholmod = solve(t, sp, b).x;
  EXPECT_LE((spectral - dense).norm(), 1e-8 * dense.norm());
  EXPECT_LE((cholmod - dense).norm(), 1e-8 * dense.norm());
  // A difference regularizer on the tensor mesh: dense and CHOLMOD agree.
  t = {{"name", "tikhonov"}, {"alpha", 1e-4}, {"regularizer", "first_difference"}, {"backend", "dense"}};
  const Eigen::VectorXd d1 = solve(t, de, b).x;
  t["backend"] = "sparse";
  EXPECT_LE((solve(t, sp, b).x - d1).norm(), 1e-8 * d1.norm());
}

TEST(DeconvRecovery, CoarseFineOperatorIsInvertedInTheLeastSquaresSense) {
  // Rectangular A (coarse data, fine solution): the minimum-norm least-squares solution reproduces the data.
  const UniformMesh1D c = UniformMesh1D::cell_centred(0, 1, 24, false), f = UniformMesh1D::cell_centred(0, 1, 72, false);
  const GaussianKernel k(c.spacing);
  const ForwardOperator a = make_averaging_operator_1d(k, c, f, Discretization::coarse_fine);
  const Eigen::VectorXd x = field(TensorMesh2D{f, UniformMesh1D{}}, 1), b = a.apply(x);
  for (const json& cfg : {json{{"name", "tsvd"}, {"k", 24}}, json{{"name", "cgls"}, {"iterations", 300}},
                          json{{"name", "tikhonov"}, {"alpha", 1e-14}}}) {
    const DeconvolutionResult r = solve(cfg, a, b);
    EXPECT_LE(r.stats.residual_norm, 1e-8 * b.norm()) << cfg.dump();
    EXPECT_EQ(r.x.size(), 72);
  }
}
