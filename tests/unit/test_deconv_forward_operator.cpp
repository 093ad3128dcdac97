// Forward operators of R_η (4.1) at the three discretizations of §4.2: Kronecker apply = dense apply,
// apply_transpose is the adjoint, sparse storage agrees, shapes, and a periodic operator reproduces the
// Fourier symbol of the kernel (4.15) on sampled modes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/reconstruction.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {
Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd v(n);
  for (auto& x : v) x = u(rng);
  return v;
}
TensorMesh2D mesh(int nx, int ny, bool periodic = false) {
  return {UniformMesh1D::cell_centred(0, 1, nx, periodic), UniformMesh1D::cell_centred(0, 0.5, ny, periodic)};
}
}  // namespace

TEST(DeconvForwardOperator, KroneckerMatchesDenseAndSparseAtEveryDiscretization) {
  const GaussianKernel k(0.08);
  const TensorMesh2D coarse = mesh(12, 7), fine = mesh(36, 21);
  for (auto d : {Discretization::coarse_coarse, Discretization::coarse_fine, Discretization::fine_fine}) {
    const ForwardOperator kr = make_averaging_operator_2d(k, coarse, fine, d, OperatorStorage::kronecker);
    const ForwardOperator de = make_averaging_operator_2d(k, coarse, fine, d, OperatorStorage::dense);
    const ForwardOperator sp = make_averaging_operator_2d(k, coarse, fine, d, OperatorStorage::sparse, 0.0);
    const Eigen::VectorXd x = random_vector(kr.cols(), 1), y = random_vector(kr.rows(), 2);
    // Same products to rounding (1e-13 relative: sums of O(100) positive terms).
    EXPECT_LE((kr.apply(x) - de.apply(x)).norm(), 1e-13 * de.apply(x).norm()) << to_string(d);
    EXPECT_LE((sp.apply(x) - de.apply(x)).norm(), 1e-13 * de.apply(x).norm()) << to_string(d);
    EXPECT_LE((kr.apply_transpose(y) - de.apply_transpose(y)).norm(), 1e-13 * de.apply_transpose(y).norm());
    // Adjointness <Ax, y> = <x, A'y>.
    EXPECT_NEAR(kr.apply(x).dot(y), x.dot(kr.apply_transpose(y)), 1e-12 * kr.apply(x).norm() * y.norm());
  }
  const ForwardOperator cf = make_averaging_operator_2d(k, coarse, fine, Discretization::coarse_fine);
  EXPECT_EQ(cf.rows(), coarse.size());
  EXPECT_EQ(cf.cols(), fine.size());
  EXPECT_FALSE(cf.is_square());
}

TEST(DeconvForwardOperator, SparseCutoffDropsOnlyNegligibleEntries) {
  const GaussianKernel k(0.03);
  const UniformMesh1D m = UniformMesh1D::cell_centred(0, 1, 200, false);
  const ForwardOperator de = make_averaging_operator_1d(k, m, m, Discretization::coarse_coarse, OperatorStorage::dense);
  const ForwardOperator sp =
      make_averaging_operator_1d(k, m, m, Discretization::coarse_coarse, OperatorStorage::sparse, 1e-14);
  EXPECT_LT(sp.sparse().nonZeros(), de.rows() * de.cols() / 2);  // the cut-off makes it genuinely sparse
  const Eigen::VectorXd x = random_vector(m.count, 3);
  EXPECT_LE((sp.apply(x) - de.apply(x)).norm(), 1e-12 * de.apply(x).norm());
}

TEST(DeconvForwardOperator, PeriodicOperatorHasTheKernelSymbolAsEigenvalue) {
  // On a periodic mesh with h <= η/2, the trapezoid sum of a Gaussian is spectrally accurate, so a Fourier
  // mode is an eigenvector with eigenvalue exp(−π²η²ξ²) (the symbol behind (4.15)) to ~1e-15.
  const double eta = 0.05;
  const GaussianKernel k(eta);
  const UniformMesh1D m = UniformMesh1D::cell_centred(0, 1, 64, true);
  const ForwardOperator a = make_averaging_operator_1d(k, m, m, Discretization::coarse_coarse);
  for (int mode : {1, 3, 7}) {
    Eigen::VectorXd v(m.count);
    for (int i = 0; i < m.count; ++i) v(i) = std::sin(2 * M_PI * mode * m.node(i));
    const double e = k.factor_symbol(mode);
    EXPECT_LE((a.apply(v) - e * v).norm(), 1e-13 * v.norm()) << "mode " << mode;
  }
}

TEST(DeconvForwardOperator, SymmetryAndNorm) {
  const GaussianKernel k(0.1);
  const TensorMesh2D c = mesh(10, 8);
  const ForwardOperator kr = make_averaging_operator_2d(k, c, c, Discretization::coarse_coarse);
  EXPECT_TRUE(kr.is_symmetric());
  const ForwardOperator de = make_averaging_operator_2d(k, c, c, Discretization::coarse_coarse, OperatorStorage::dense);
  EXPECT_NEAR(kr.norm2_estimate(), de.norm2_estimate(), 1e-12);
  const ForwardOperator sp =
      make_averaging_operator_2d(k, c, c, Discretization::coarse_coarse, OperatorStorage::sparse);
  EXPECT_NEAR(sp.norm2_estimate(), de.norm2_estimate(), 1e-8);  // power iteration
}

TEST(DeconvReconstruction, SamplesLinearFieldsExactlyAndWrapsPeriodicAxes) {
  const TensorMesh2D m = mesh(9, 5);
  Eigen::VectorXd v(m.size());
  for (int j = 0; j < m.ny(); ++j)
    for (int i = 0; i < m.nx(); ++i) v(m.index(i, j)) = 2.0 * m.x.node(i) - 3.0 * m.y.node(j) + 1.0;
  const Reconstruction r(m, 2, v);
  for (const Vec2& p : {Vec2(0.3, 0.2), Vec2(0.71, 0.33), Vec2(m.x.node(4), m.y.node(2))})
    EXPECT_NEAR(r.sample(p), 2.0 * p.x() - 3.0 * p.y() + 1.0, 1e-14);
  const UniformMesh1D pm = UniformMesh1D::cell_centred(0, 1, 16, true);
  Eigen::VectorXd w(16);
  for (int i = 0; i < 16; ++i) w(i) = std::cos(2 * M_PI * pm.node(i));
  const Reconstruction pr(TensorMesh2D{pm, UniformMesh1D{}}, 1, w);
  EXPECT_NEAR(pr.sample(Vec2(0.01, 0)), pr.sample(Vec2(1.01, 0)), 1e-14);
}

TEST(DeconvReconstruction, ASolutionOnTheFineMeshIsSampledAtArbitraryPoints) {
  // Coarse–fine discretization: the solution lives on the fine mesh and is a field sampled anywhere.
  const GaussianKernel k(0.1);
  const UniformMesh1D c = UniformMesh1D::cell_centred(0, 1, 10, false),
                      f = UniformMesh1D::cell_centred(0, 1, 40, false);
  const ForwardOperator a = make_averaging_operator_1d(k, c, f, Discretization::coarse_fine);
  Eigen::VectorXd x(40);
  for (int i = 0; i < 40; ++i) x(i) = 3.0 * f.node(i) - 1.0;
  const Reconstruction r = reconstruction_of(a, x);
  EXPECT_NEAR(r.sample(Vec2(0.4321, 0.0)), 3.0 * 0.4321 - 1.0, 1e-14);
  EXPECT_THROW(
      reconstruction_of(ForwardOperator::from_dense(Eigen::MatrixXd::Identity(3, 3)), Eigen::VectorXd::Ones(3)),
      ConfigError);
}

// Both components of a velocity sampled with one location per point equal each component's own samples to the bit,
// on a periodic and on a bounded mesh (points beyond the ends clamp).
TEST(Reconstruction, SamplePairEqualsEachComponentsSamples) {
  for (const bool periodic : {true, false}) {
    const TensorMesh2D m{UniformMesh1D::cell_centred(0.0, 1.0, 7, periodic),
                         UniformMesh1D::cell_centred(0.0, 2.0, 5, periodic)};
    const Eigen::VectorXd a = Eigen::VectorXd::Random(m.size()), b = Eigen::VectorXd::Random(m.size());
    const Reconstruction x(m, 2, a), y(m, 2, b);
    std::vector<Vec2> points;
    for (int k = 0; k < 200; ++k) points.emplace_back(-0.3 + 0.0083 * k, 2.4 - 0.013 * k);
    const Eigen::Matrix2Xd both = sample_pair(x, y, points);
    const Eigen::VectorXd sx = x.sample(points), sy = y.sample(points);
    for (int k = 0; k < 200; ++k) {
      EXPECT_EQ(both(0, k), sx[k]);
      EXPECT_EQ(both(1, k), sy[k]);
    }
  }
}
