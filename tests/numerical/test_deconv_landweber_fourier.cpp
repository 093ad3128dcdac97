// Landweber of order n, (4.3)/(4.9), reproduces the Fourier prediction of (4.15): on a periodic mesh a mode of
// frequency ξ averaged by the Gaussian has amplitude e = exp(−π²η²|ξ|²), and x_n = Σ_{k<=n}(I − A)^k b has
// amplitude 1 − (1 − e)^{n+1} times the true one. With h <= η/2 the sampled operator has the mode as an
// eigenvector with eigenvalue e to ~1e-16 (trapezoid rule on a periodic Gaussian), so the prediction holds to
// rounding: tolerance 1e-12.
#include <gtest/gtest.h>

#include <cmath>

#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/reconstruction.hpp"
#include "core/base/registry.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {
DeconvolutionResult landweber(const ForwardOperator& a, const Eigen::VectorXd& b, int order) {
  auto d = builtin_registry().deconvolvers.create(json{{"name", "landweber"}, {"order", order}}, "/m");
  d->setup(a);
  return d->solve(b);
}
}  // namespace

TEST(DeconvLandweberFourier, OrderNReproducesOneMinusOneMinusEToTheNPlusOne1D) {
  const double eta = 0.06;
  const GaussianKernel k(eta);
  const UniformMesh1D m = UniformMesh1D::cell_centred(0, 1, 64, true);  // h = η/3.84
  const ForwardOperator a = make_averaging_operator_1d(k, m, m, Discretization::coarse_coarse);
  for (int mode : {1, 2, 5}) {
    const double e = std::exp(-M_PI * M_PI * eta * eta * mode * mode);  // (4.15): 1 − e is the symbol of I − R_η
    Eigen::VectorXd truth(m.count);
    for (int i = 0; i < m.count; ++i) truth(i) = std::sin(2 * M_PI * mode * m.node(i));
    const Eigen::VectorXd b = e * truth;  // exact Gaussian average of the mode
    for (int n : {0, 1, 2, 5, 20}) {
      const DeconvolutionResult r = landweber(a, b, n);
      const double predicted = 1.0 - std::pow(1.0 - e, n + 1);
      EXPECT_EQ(r.status, DeconvolutionStatus::converged);
      EXPECT_LE((r.x - predicted * truth).norm(), 1e-12 * truth.norm()) << "mode " << mode << " order " << n;
      EXPECT_EQ(r.cost.matvecs, n + 1);  // n products for x_n, one for its residual
      // The bare series (no residual) costs exactly n separable convolutions and gives the same x.
      auto bare = builtin_registry().deconvolvers.create(json{{"name", "landweber"}, {"order", n}, {"report_residual", false}}, "/m");
      bare->setup(a);
      const DeconvolutionResult rb = bare->solve(b);
      EXPECT_EQ(rb.cost.matvecs, n);
      EXPECT_LE((rb.x - r.x).norm(), 1e-14 * r.x.norm());
    }
  }
}

TEST(DeconvLandweberFourier, OrderNReproducesThePredictionOnA2DTensorMesh) {
  const double eta = 0.05;
  const GaussianKernel k(eta);
  const TensorMesh2D m{UniformMesh1D::cell_centred(0, 1, 48, true), UniformMesh1D::cell_centred(0, 0.5, 24, true)};
  const ForwardOperator a = make_averaging_operator_2d(k, m, m, Discretization::coarse_coarse);  // A_y ⊗ A_x
  const double xi_x = 3.0, xi_y = 2.0 / 0.5;
  const double e = std::exp(-M_PI * M_PI * eta * eta * (xi_x * xi_x + xi_y * xi_y));  // (4.15), ξ·ξ
  Eigen::VectorXd truth(m.size());
  for (int j = 0; j < m.ny(); ++j)
    for (int i = 0; i < m.nx(); ++i)
      truth(m.index(i, j)) = std::sin(2 * M_PI * xi_x * m.x.node(i)) * std::cos(2 * M_PI * xi_y * m.y.node(j));
  for (int n : {1, 2, 4}) {
    const DeconvolutionResult r = landweber(a, e * truth, n);
    EXPECT_LE((r.x - (1.0 - std::pow(1.0 - e, n + 1)) * truth).norm(), 1e-12 * truth.norm()) << "order " << n;
  }
}

TEST(DeconvLandweberFourier, CoarseFineInterpolationOfTheSeriesIsSecondOrder) {
  // §4.2: the coarse series rendered at fine points (b interpolated linearly, A replaced by the coarse–fine
  // quadrature of the kernel) converges to the Fourier prediction like H² (linear interpolation).
  const double eta = 0.05;
  const GaussianKernel k(eta);
  const int mode = 3;
  const double e = k.factor_symbol(mode);
  std::vector<Vec2> points;
  for (int j = 0; j < 997; ++j) points.push_back(Vec2((j + 0.37) / 997.0, 0.0));
  for (int n : {0, 1, 2}) {
    std::vector<double> err;
    for (int count : {64, 128, 256}) {
      const UniformMesh1D c = UniformMesh1D::cell_centred(0, 1, count, true);
      Eigen::VectorXd b(count);
      for (int i = 0; i < count; ++i) b(i) = e * std::sin(2 * M_PI * mode * c.node(i));
      const Eigen::VectorXd v = landweber_series_at_points(k, TensorMesh2D{c, UniformMesh1D{}}, 1, b, n, points);
      double worst = 0;
      for (size_t q = 0; q < points.size(); ++q)
        worst = std::max(worst, std::abs(v(static_cast<Eigen::Index>(q)) -
                                         (1 - std::pow(1 - e, n + 1)) * std::sin(2 * M_PI * mode * points[q].x())));
      err.push_back(worst);
    }
    EXPECT_LT(err[0], 0.03) << "order " << n;
    for (size_t i = 0; i + 1 < err.size(); ++i) {
      EXPECT_GT(err[i] / err[i + 1], 3.5) << "order " << n;  // second order: ratio 4 per halving of H
      EXPECT_LT(err[i] / err[i + 1], 4.5) << "order " << n;
    }
  }
}
