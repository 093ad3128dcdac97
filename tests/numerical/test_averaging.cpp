// Averaging operators against analytic averages: (2.9) on a lattice carrying the Poiseuille parabola vs
// (B.2) and GSL quadrature; the convective stress (2.12) vs Appendix B and its η² scaling.
#include <gtest/gtest.h>

#include <cmath>

#include "core/scenes/analytic.hpp"
#include "core/averaging/averaging.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {

// A square lattice of spacing dx filling [0, lx) x [ylo, yhi), unit density, velocity v(y) along x.
ParticleSystem lattice(double dx, int nx, double ylo, double yhi, const std::function<double(double)>& v) {
  ParticleSystem ps;
  for (double y = ylo + 0.5 * dx; y < yhi; y += dx)
    for (int i = 0; i < nx; ++i) {
      ps.add((i + 0.5) * dx, y, dx * dx, 0, false);
      ps.vx.back() = v(y);
    }
  return ps;
}

const double l1 = 0.1875, l2 = 0.8125;  // walls of the canonical channel (η' = 1/16)

double parabola(double y) { return -0.5 * (y * y - (l1 + l2) * y + l1 * l2); }  // (5.15) continued, ρ g / μ = 1

}  // namespace

TEST(AveragingFormulas, B2IsTheGaussianAverageOfTheParabola) {
  for (double eta : {1.0 / 32, 1.0 / 16, 0.1}) {
    GaussianKernel k(eta);
    for (double y : {0.3, 0.5, 0.77}) {
      const double q = average_by_quadrature(parabola, [&](double t) { return k.factor(t); }, k.support_radius(), y,
                                             -10.0, 10.0);
      EXPECT_NEAR(poiseuille_averaged_b2(y, l1, l2, 1, 1, 1, eta), q, 1e-13);
    }
  }
}

TEST(AveragingOperators, LatticeAverageOfParabolaMatchesB2) {
  // The Riemann sums (2.8)–(2.9) of a Gaussian over a lattice of spacing ε' ≪ η' are exact up to
  // exp(−π² η'² / ε'²) (Poisson summation): here ≈ e^{−89}, so only round-off remains.
  const double eta = 1.0 / 16, dx = 1.0 / 192;
  GaussianKernel k(eta);
  ParticleSystem ps = lattice(dx, 12, -0.5, 1.5, parabola);
  const PeriodicBox box{12 * dx, 2.0, true, false};
  TensorMesh2D mesh{UniformMesh1D{0.0, box.lx, 1, true, box.lx}, UniformMesh1D{0.25, 0.05, 11, false, 0.0}};
  AveragingRequest req;
  req.convective = true;
  req.components = {"xx", "xy"};
  const MesoFields f = average_particles(ps, box, k, mesh, req);
  for (int n = 0; n < mesh.size(); ++n) {
    const double y = mesh.node(n).y();
    EXPECT_NEAR(f.rho[n], 1.0, 1e-12);                                                   // (2.8)
    EXPECT_NEAR(f.vx[n], poiseuille_averaged_b2(y, l1, l2, 1, 1, 1, eta), 1e-13);        // (2.9) vs (B.2)
    EXPECT_NEAR(f.vy[n], 0.0, 1e-15);
    // (2.12) vs Appendix B: −T_c,xx / ρ is the variance of V under the window; T_c,xy = 0.
    EXPECT_NEAR(-f.convective.at("xx")[n], poiseuille_convective_stress_b(y, l1, l2, 1, 1, 1, eta), 1e-12);
    EXPECT_NEAR(f.convective.at("xy")[n], 0.0, 1e-15);
  }
}

TEST(AveragingOperators, ConvectiveStressShrinksLikeEtaSquared) {
  // Appendix B: away from the channel centre T_c,xx = −(ρg/2μ)² [(l1 + l2 − 2y)² η²/2 + η⁴/2]: order η².
  const double dx = 1.0 / 384, y = 0.3;
  ParticleSystem ps = lattice(dx, 24, -0.5, 1.5, parabola);
  const PeriodicBox box{24 * dx, 2.0, true, false};
  TensorMesh2D mesh{UniformMesh1D{0.0, box.lx, 1, true, box.lx}, UniformMesh1D{y, 1.0, 1, false, 0.0}};
  AveragingRequest req;
  req.convective = true;
  req.components = {"xx"};
  std::vector<double> etas = {1.0 / 64, 1.0 / 32, 1.0 / 16}, tc;
  for (double eta : etas) tc.push_back(-average_particles(ps, box, GaussianKernel(eta), mesh, req).convective.at("xx")[0]);
  for (std::size_t i = 1; i < etas.size(); ++i) {
    const double order = std::log(tc[i] / tc[i - 1]) / std::log(etas[i] / etas[i - 1]);
    EXPECT_NEAR(order, 2.0, 0.05) << "eta " << etas[i];
  }
}

TEST(AveragingOperators, MeshPeriodicityMustMatchTheBox) {
  ParticleSystem ps = lattice(0.1, 4, 0.0, 1.0, parabola);
  const PeriodicBox box{0.4, 1.0, true, false};
  TensorMesh2D wrong{UniformMesh1D{0.0, 0.1, 4, false, 0.0}, UniformMesh1D{0.5, 0.1, 1, false, 0.0}};
  EXPECT_THROW(average_particles(ps, box, GaussianKernel(0.1), wrong, AveragingRequest{}), std::exception);
}
