// Averaging kernels (2.6)–(2.7), their Fourier symbols (4.15) and the bond integral of Appendix A,
// each against GSL adaptive quadrature.
#include <gsl/gsl_integration.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/base/gsl_support.hpp"
#include "core/sph/sph_kernel.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"
#include "strategies/kernels/gaussian_segment.hpp"

using namespace closurelab;

namespace {

// Adaptive quadrature of f over [a, b] (QAGS handles the cut-off kernel's jumps); relative target 2e-14 (GSL refuses below 50 ulp).
double integrate(const std::function<double(double)>& f, double a, double b, double epsrel = 2e-14) {
  gsl_errors_as_status();
  gsl_function F;
  F.function = [](double x, void* p) { return (*static_cast<const std::function<double(double)>*>(p))(x); };
  F.params = const_cast<std::function<double(double)>*>(&f);
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(5000);
  double r = 0, err = 0;
  const int status = gsl_integration_qags(&F, a, b, 0.0, epsrel, 5000, w, &r, &err);
  gsl_integration_workspace_free(w);
  // GSL may report that 1e-14 is not reachable in round-off; its own error estimate must still be tiny (relative, or absolute for values below 1).
  EXPECT_TRUE(status == 0 || err <= 1e-13 * std::max(1.0, std::abs(r))) << "quadrature status " << status << " err " << err;
  return r;
}

double bond_by_quadrature(const AveragingKernel& k, const Vec2& x, const Vec2& qj, const Vec2& qk) {
  return integrate([&](double s) { return k.value(s * (x - qk) + (1 - s) * (x - qj)); }, 0.0, 1.0);
}

}  // namespace

TEST(GaussianKernel, NormalizationIsOne) {  // (2.6)
  for (double eta : {0.01, 0.0625, 1.0}) {
    GaussianKernel k(eta);
    const double one_d = integrate([&](double t) { return k.factor(t); }, -k.support_radius(), k.support_radius());
    EXPECT_NEAR(one_d, 1.0, 1e-12);
    EXPECT_NEAR(one_d * one_d, 1.0, 1e-12);  // ψ = φ(x) φ(y)
    EXPECT_NEAR(k.value(Vec2(0, 0)), 1.0 / (M_PI * eta * eta), 1e-12 / (eta * eta));  // (2.7)
  }
}

TEST(GaussianKernel, FourierSymbolMatchesQuadratureAnd415) {
  const double eta = 0.07;
  GaussianKernel k(eta);
  for (double xi : {0.0, 1.0, 3.0, 7.5}) {
    const double q = integrate([&](double t) { return k.factor(t) * std::cos(2 * M_PI * xi * t); }, -k.support_radius(),
                               k.support_radius());
    EXPECT_NEAR(k.factor_symbol(xi), q, 1e-12);
    // (4.15): the symbol of I − R_η is 1 − exp(−η² π² |ξ|²).
    const Vec2 v(xi, 0.5 * xi);
    EXPECT_NEAR(1.0 - k.symbol(v), 1.0 - std::exp(-eta * eta * M_PI * M_PI * v.squaredNorm()), 1e-15);
  }
}

TEST(CutoffGaussianKernel, NormalizationAndSymbol) {
  for (double cutoff : {2.0, 3.0}) {
    CutoffGaussianKernel k(0.05, cutoff);
    EXPECT_NEAR(integrate([&](double t) { return k.factor(t); }, -0.2, 0.2), 1.0, 1e-12);
    EXPECT_EQ(k.factor(cutoff * 0.05 * 1.0001), 0.0);
    EXPECT_NEAR(k.factor_symbol(0.0), 1.0, 1e-12);
  }
  // Truncation at 2η (about 2.8σ) makes the symbol negative at some frequency: the sampled operator can
  // have negative eigenvalues (DESIGN.md §6).
  CutoffGaussianKernel k(1.0, 2.0);
  double most_negative = 1.0;
  for (double xi = 0.0; xi < 3.0; xi += 0.01) most_negative = std::min(most_negative, k.factor_symbol(xi));
  EXPECT_LT(most_negative, 0.0);
}

struct BondCase {
  const char* what;
  Vec2 x, qj, qk;
};

class BondIntegral : public ::testing::TestWithParam<BondCase> {};

TEST_P(BondIntegral, MatchesGslQuadratureTo1e12) {
  const auto& c = GetParam();
  const double eta = 0.0625;
  GaussianKernel k(eta);
  const Vec2 x = eta * c.x, qj = eta * c.qj, qk = eta * c.qk;
  const double ref = bond_by_quadrature(k, x, qj, qk);
  const double got = k.bond_integral(x, qj, qk);
  ASSERT_GT(ref, 0.0);
  EXPECT_LE(std::abs(got - ref) / ref, 1e-12) << c.what << ": got " << got << " ref " << ref;
  // Symmetric in the two ends (s → 1 − s).
  EXPECT_LE(std::abs(k.bond_integral(x, qk, qj) - got) / ref, 1e-13) << c.what;
}

// Positions in units of η: near (window centre on or beside the bond), far (the printed erf difference
// cancels), and degenerate (|q_k − q_j| → 0).
INSTANTIATE_TEST_SUITE_P(
    Configurations, BondIntegral,
    ::testing::Values(BondCase{"centre on bond", {0.1, 0.0}, {0.0, 0.0}, {0.3, 0.0}},
                      BondCase{"near, oblique", {0.5, 0.7}, {0.2, -0.1}, {0.4, 0.25}},
                      BondCase{"long bond across centre", {0.0, 0.2}, {-2.0, -1.0}, {2.5, 1.5}},
                      BondCase{"far along the bond", {5.0, 0.0}, {0.0, 0.0}, {0.05, 0.0}},
                      BondCase{"far, oblique", {-4.0, 3.0}, {0.0, 0.0}, {0.04, 0.03}},
                      BondCase{"very far", {5.5, 0.0}, {0.0, 0.0}, {0.5, 0.0}},
                      BondCase{"far beyond end", {3.0, 0.4}, {0.0, 0.0}, {1.0, 0.0}},
                      BondCase{"short bond", {0.7, 0.3}, {0.0, 0.0}, {1e-4, 0.0}},
                      BondCase{"tiny bond", {1.2, -0.4}, {0.0, 0.0}, {1e-9, 1e-9}},
                      BondCase{"zero bond", {0.3, 0.3}, {0.1, 0.1}, {0.1, 0.1}},
                      BondCase{"SPH-size bond, far", {2.9, 1.0}, {0.0, 0.0}, {0.25, 0.125}}));

TEST(BondIntegralLimit, ShortBondTendsToPsi) {
  GaussianKernel k(0.1);
  const Vec2 x(0.03, -0.07), q(0.01, 0.02);
  for (double len : {1e-3, 1e-6, 1e-9}) {
    const double b = k.bond_integral(x, q, q + Vec2(len, 0.5 * len));
    EXPECT_NEAR(b / k.value(x - q), 1.0, 20 * len / 0.1 + 1e-14);
  }
  EXPECT_NEAR(k.bond_integral(x, q, q) / k.value(x - q), 1.0, 1e-15);
}

TEST(CutoffBondIntegral, MatchesQuadrature) {
  CutoffGaussianKernel k(0.0625, 3.0);
  const double eta = 0.0625;
  const std::vector<std::array<Vec2, 3>> cases = {{Vec2(0.1, 0), Vec2(0, 0), Vec2(0.3, 0.1)},
                                                  {Vec2(2.9, 0.5), Vec2(0, 0), Vec2(0.4, 0.1)},   // crosses the cut
                                                  {Vec2(1.0, 2.95), Vec2(0, 0), Vec2(0.2, -0.2)},  // crosses the cut
                                                  {Vec2(0.5, 0.5), Vec2(0.2, 0.2), Vec2(0.2, 0.2)}};
  for (const auto& c : cases) {
    const Vec2 x = eta * c[0], qj = eta * c[1], qk = eta * c[2];
    const double ref = integrate([&](double s) { return k.value(s * (x - qk) + (1 - s) * (x - qj)); }, 0.0, 1.0, 1e-13);
    EXPECT_NEAR(k.bond_integral(x, qj, qk), ref, 1e-11 * std::abs(ref) + 1e-300);
  }
  EXPECT_EQ(k.bond_integral(Vec2(10 * eta, 0), Vec2(0, 0), Vec2(0.1 * eta, 0)), 0.0);
}

TEST(Erfcx, MatchesDefinitionWhereItIsRepresentable) {
  for (double x : {0.0, 0.3, 1.0, 4.0, 10.0}) EXPECT_NEAR(erfcx(x), std::exp(x * x) * std::erfc(x), 1e-13 * erfcx(x));
  EXPECT_NEAR(erfcx(1e6), 1.0 / (std::sqrt(M_PI) * 1e6), 1e-12 / 1e6);  // asymptote, where exp(x²) overflows
}

TEST(SmoothingKernel, NormalizedWithConsistentDerivative) {  // (5.2)
  for (const char* name : {"quintic", "wendland_c2"}) {
    const double h = 0.01;
    const SmoothingKernel w = SmoothingKernel(parse_name<SmoothingKernel::Type>(name, "/smoothing_kernel"), h);
    const double mass = 2 * M_PI * integrate([&](double r) { return w.w(r) * r; }, 0.0, w.support());
    EXPECT_NEAR(mass, 1.0, 1e-12) << name;
    for (double r : {0.3 * h, 1.2 * h, 1.9 * h}) {
      const double fd = (w.w(r + 1e-7 * h) - w.w(r - 1e-7 * h)) / (2e-7 * h);
      EXPECT_NEAR(w.dw(r), fd, 1e-6 * std::abs(fd)) << name << " r/h=" << r / h;
    }
    EXPECT_EQ(w.w(w.support()), 0.0);
  }
}
