// The Landweber series with the interpolation lift (lift = interpolation, the known zeros): on a channel's
// coarse–fine operator (data on the coarse nodes, the wall-surface nodes included; unknowns the fluid rows only,
// the wall rows beyond them known zeros) it equals the dense formula x_n = J Σ_{k<=n} (I − A J)^k b with J built
// here independently (linear interpolation written out), order 0 is J b, the reported residual is ‖b − A x_n‖, and
// as n grows x_n converges to J c* with A J c* = b (on data from a coarse field, that field's interpolant).
// The reported ‖x_n‖ is that of J c_n; the discrepancy rule stops the lifted series at the first order within τδ.
// lift = none is the series as before, bit for bit; lift = interpolation on a square operator whose two meshes
// are the same (J = I) is the plain series; the lift refuses a plain matrix, and none refuses a rectangular A.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {

// A channel of width 1: coarse nodes on both walls and evenly between (16 intervals), 96 fluid rows.
const UniformMesh1D kCoarse{0.0, 1.0 / 16, 17, false, 0.0};
const UniformMesh1D kFine = UniformMesh1D::cell_centred(0.0, 1.0, 96, false);

std::unique_ptr<Deconvolver> landweber(const ForwardOperator& a, int order, const std::string& lift,
                                       bool report_residual = true) {
  auto d = builtin_registry().deconvolvers.create(
      json{{"name", "landweber"}, {"order", order}, {"lift", lift}, {"report_residual", report_residual}}, "/method");
  d->setup(a);
  return d;
}

// Linear interpolation of the coarse nodes at the fine nodes, written out (not via Reconstruction).
Eigen::MatrixXd interpolation(const UniformMesh1D& from, const UniformMesh1D& to) {
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(to.count, from.count);
  for (int r = 0; r < to.count; ++r) {
    const double s = (to.node(r) - from.origin) / from.spacing;
    const int i = std::min(static_cast<int>(std::floor(s)), from.count - 2);
    j(r, i) = 1.0 - (s - i);
    j(r, i + 1) = s - i;
  }
  return j;
}

Eigen::VectorXd channel_data() {  // averages of a parabola-like profile at the coarse nodes (any data will do)
  Eigen::VectorXd b(kCoarse.count);
  for (int i = 0; i < kCoarse.count; ++i) {
    const double y = kCoarse.node(i);
    b[i] = 0.1 + 3.0 * y * (1.0 - y) + 0.05 * std::sin(7.0 * y);
  }
  return b;
}

}  // namespace

TEST(DeconvLandweberLift, EqualsTheDenseSeriesOnAChannelsCoarseFineOperator) {
  const GaussianKernel k(1.0 / 16);
  const ForwardOperator a = make_averaging_operator_1d(k, kCoarse, kFine, Discretization::coarse_fine);
  ASSERT_EQ(a.rows(), 17);
  ASSERT_EQ(a.cols(), 96);  // the unknowns are the fluid rows: the wall rows are not unknowns (known zeros)
  const Eigen::MatrixXd ad = a.to_dense(), j = interpolation(kCoarse, kFine);
  const Eigen::MatrixXd m = Eigen::MatrixXd::Identity(17, 17) - ad * j;
  const Eigen::VectorXd b = channel_data();
  Eigen::VectorXd c = Eigen::VectorXd::Zero(17), term = b;
  for (int n = 0; n <= 6; ++n) {
    c += term;  // c = Σ_{k<=n} (I − A J)^k b
    term = m * term;
    const Eigen::VectorXd expected = j * c;
    for (bool report : {true, false}) {
      const DeconvolutionResult r = landweber(a, n, "interpolation", report)->solve(b);
      ASSERT_EQ(r.status, Status::converged) << r.stats.message;
      ASSERT_EQ(r.x.size(), 96);
      EXPECT_LE((r.x - expected).norm(), 1e-13 * expected.norm()) << "order " << n;
      EXPECT_EQ(r.stats.chosen_parameter, n);
      EXPECT_NEAR(r.stats.solution_norm, expected.norm(), 1e-13 * expected.norm()) << "order " << n;
      if (report) {
        EXPECT_NEAR(r.stats.residual_norm, (b - ad * r.x).norm(), 1e-13 * b.norm()) << "order " << n;
      }
    }
  }
  // Order 0 is the average interpolated to the fluid rows ((4.11) rendered on the fine mesh).
  const DeconvolutionResult r0 = landweber(a, 0, "interpolation")->solve(b);
  EXPECT_LE((r0.x - j * b).cwiseAbs().maxCoeff(), 1e-15 * b.cwiseAbs().maxCoeff());
}

TEST(DeconvLandweberLift, ConvergesToTheInterpolantOfTheCoarseSolution) {
  // η = H/2: A J is well conditioned, its spectrum in (0, 2), so c_n → (A J)⁻¹ b geometrically. Data from a coarse
  // field c* (b = A J c*): x_n → J c*, the field rendered on the fluid rows with the wall rows at their zero.
  const GaussianKernel k(1.0 / 32);
  const ForwardOperator a = make_averaging_operator_1d(k, kCoarse, kFine, Discretization::coarse_fine);
  const Eigen::MatrixXd aj = a.to_dense() * interpolation(kCoarse, kFine);
  const Eigen::VectorXcd ev = aj.eigenvalues();
  double rho = 0.0;  // spectral radius of I − A J
  for (Eigen::Index i = 0; i < ev.size(); ++i) {
    ASSERT_GT(ev[i].real(), 0.0);
    ASSERT_LT(ev[i].real(), 2.0);
    rho = std::max(rho, std::abs(std::complex<double>(1.0, 0.0) - ev[i]));
  }
  ASSERT_LT(rho, 0.9);
  const Eigen::VectorXd cstar = channel_data(), b = aj * cstar;
  const Eigen::VectorXd target = interpolation(kCoarse, kFine) * cstar;
  double previous = INFINITY;
  for (int n : {0, 5, 20, 80, 320}) {
    const DeconvolutionResult r = landweber(a, n, "interpolation")->solve(b);
    const double err = (r.x - target).norm() / target.norm();
    EXPECT_LT(err, previous) << "order " << n;
    previous = err;
  }
  EXPECT_LT(previous, 1e-10);
}

TEST(DeconvLandweberLift, NoneIsThePaperSeriesBitForBitAndTheLiftOfEqualMeshesIsTheIdentity) {
  const GaussianKernel k(0.07);
  const UniformMesh1D periodic = UniformMesh1D::cell_centred(0.0, 1.0, 24, true);
  const ForwardOperator a = make_averaging_operator_1d(k, periodic, periodic, Discretization::coarse_coarse);
  Eigen::VectorXd b(24);
  for (int i = 0; i < 24; ++i) b[i] = std::sin(2 * M_PI * periodic.node(i)) + 0.3 * std::cos(6 * M_PI * periodic.node(i));
  for (int n : {0, 1, 2, 5}) {
    Eigen::VectorXd x = b, u = b;  // the recursion (4.9) as the series was always computed
    for (int q = 1; q <= n; ++q) {
      u -= a.apply(u);
      x += u;
    }
    for (bool report : {true, false}) {
      const DeconvolutionResult r = landweber(a, n, "none", report)->solve(b);
      for (Eigen::Index i = 0; i < 24; ++i) ASSERT_EQ(r.x[i], x[i]) << "order " << n;  // bit for bit
      auto d = builtin_registry().deconvolvers.create(
          json{{"name", "landweber"}, {"order", n}, {"report_residual", report}}, "/m");  // lift by default
      d->setup(a);
      const DeconvolutionResult rd = d->solve(b);
      for (Eigen::Index i = 0; i < 24; ++i) ASSERT_EQ(rd.x[i], x[i]) << "default lift, order " << n;
      const DeconvolutionResult ri = landweber(a, n, "interpolation", report)->solve(b);
      EXPECT_LE((ri.x - x).cwiseAbs().maxCoeff(), 1e-14 * x.cwiseAbs().maxCoeff()) << "order " << n;
    }
  }
}

TEST(DeconvLandweberLift, RefusesWhatItCannotServe) {
  const GaussianKernel k(1.0 / 16);
  const ForwardOperator cf = make_averaging_operator_1d(k, kCoarse, kFine, Discretization::coarse_fine);
  try {
    landweber(cf, 1, "none");
    FAIL() << "a rectangular operator without the lift";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("lift = interpolation"), std::string::npos) << e.what();
  }
  const ForwardOperator plain = ForwardOperator::from_dense(cf.to_dense());
  try {
    landweber(plain, 1, "interpolation");
    FAIL() << "a plain matrix carries no meshes";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/lift") << e.what();
  }
  EXPECT_THROW(builtin_registry().deconvolvers.create(json{{"name", "landweber"}, {"lift", "projected"}}, "/m"),
               ConfigError);
}

TEST(DeconvLandweberLift, TheDiscrepancyRuleStopsTheLiftedSeries) {
  // The rules walk the same scan: on data with noise of norm δ the discrepancy principle stops at the first order
  // whose residual ‖b − A x_n‖ is within τ δ, and the solution is that order's J c_n.
  const GaussianKernel k(1.0 / 32);
  const ForwardOperator a = make_averaging_operator_1d(k, kCoarse, kFine, Discretization::coarse_fine);
  const Eigen::MatrixXd aj = a.to_dense() * interpolation(kCoarse, kFine);
  Eigen::VectorXd noise(17);
  for (int i = 0; i < 17; ++i) noise[i] = 1e-3 * std::cos(5.0 * i);
  const Eigen::VectorXd b = aj * channel_data() + noise;
  auto d = builtin_registry().deconvolvers.create(
      json{{"name", "landweber"}, {"lift", "interpolation"}, {"rule", "discrepancy"}, {"max_order", 1000}}, "/m");
  d->setup(a);
  const DeconvolutionResult r = d->solve(b, noise.norm());
  ASSERT_EQ(r.status, Status::converged) << r.stats.message;
  const int n = static_cast<int>(r.stats.chosen_parameter);
  EXPECT_GT(n, 0);
  EXPECT_LT(n, 1000);
  EXPECT_LE((b - a.apply(r.x)).norm(), 1.01 * noise.norm() * (1 + 1e-12));
  const DeconvolutionResult fixed = landweber(a, n, "interpolation")->solve(b);
  EXPECT_LE((r.x - fixed.x).norm(), 1e-14 * fixed.x.norm());
  const Eigen::VectorXd before = landweber(a, n - 1, "interpolation")->solve(b).x;  // n > 0 asserted above
  EXPECT_GT((b - a.apply(before)).norm(), 1.01 * noise.norm());
}
