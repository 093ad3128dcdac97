// The exact stress quadrature (2.13) against the averaging operator, the virial identity, and the
// continuum limit of a linear shear; the coarse quadrature (5.27) on the same shear.
#include <gtest/gtest.h>

#include "core/averaging/averaging.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_kernel.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"
#include "strategies/quadrature/coarse_quadrature.hpp"
#include "strategies/quadrature/exact_quadrature.hpp"
#include "tests/support/quadrature_support.hpp"

using namespace closurelab;
using namespace closurelab::quadrature_test;

namespace {

const std::vector<std::string> kAll{"xx", "xy", "yx", "yy"};

// A general (x-dependent, two-component) field on the channel: Poiseuille plus periodic perturbations.
Vec2 general_field(const Scene& s, const Vec2& q) {
  const double k = 2.0 * M_PI / s.box.lx;
  return {s.analytic_vx(q.y()) + 0.01 * std::sin(k * q.x()) * q.y(), 0.02 * std::cos(k * q.x() + 3.0 * q.y())};
}

// average_particles' interaction stress for the same velocities (the reference the exact quadrature must
// reproduce): particles with the field on the fluid, walls at rest, pair forces from the SPH engine.
std::map<std::string, Eigen::VectorXd> averaged_reference(const Scene& s, const AveragingKernel& k,
                                                          const TensorMesh2D& mesh) {
  ParticleSystem ps = s.make_particles();
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) {
      const Vec2 v = general_field(s, Vec2(ps.x[a], ps.y[a]));
      ps.vx[a] = v.x();
      ps.vy[a] = v.y();
    }
  SphEngine engine(s, ps);
  AveragingRequest req;
  req.interaction = true;
  req.components = kAll;
  return average_particles(ps, s.box, k, mesh, req, engine.pair_forces()).interaction;
}

}  // namespace

// Same pairs, same forces, same bond integrals: the tabulated sum must agree with the averaging operator to
// round-off (1e-12 of the largest stress component; the sums differ only in summation order).
TEST(ExactQuadrature, ReproducesAveragedInteractionStress) {
  for (const std::string walls : {"zero_velocity", "ghost_velocity"}) {
    const auto s = channel(48, 1.0 / 16, 12, walls);
    const GaussianKernel k(s->eta);
    const TensorMesh2D mesh{UniformMesh1D::cell_centred(0.0, s->box.lx, 3, true),
                            UniformMesh1D::cell_centred(0.0, s->box.ly, 40, false)};
    ExactQuadrature q;
    q.setup(*s, k, mesh, kAll);
    const QuadratureResult r = q.evaluate(sampler_of(*s, [&](const Vec2& p) { return general_field(*s, p); }));
    ASSERT_EQ(r.status, Status::converged) << r.message;
    const auto [diff, scale] = max_difference(r.stress, averaged_reference(*s, k, mesh));
    EXPECT_GT(scale, 0.0);
    EXPECT_LE(diff, 1e-12 * scale) << walls;
    EXPECT_EQ(r.pair_forces, static_cast<long>(q.pair_count()));
  }
}

// ∫ T_int over a periodic box = Σ f_jk ⊗ (q_k − q_j) exactly; the trapezoid rule on the periodic node mesh is
// spectrally accurate for the smooth periodic integrand (error ~ exp(−π² η²/Δ²) ≈ 1e-21), so 1e-12.
TEST(ExactQuadrature, VirialIdentityOnAPeriodicBox) {
  const Scene s = periodic_box(16, 0.5);
  const auto field = [](const Vec2& p) {
    return Vec2(std::sin(4.0 * M_PI * p.y()) + 0.3 * std::cos(4.0 * M_PI * p.x()), 0.2 * std::sin(4.0 * M_PI * p.x()));
  };
  const auto axis = UniformMesh1D::cell_centred(0.0, 0.5, 14, true);
  const TensorMesh2D mesh{axis, axis};
  ExactQuadrature q;
  q.setup(s, GaussianKernel(0.08), mesh, kAll);
  const auto t = q.evaluate(sampler_of(s, field)).stress;
  ParticleSystem ps = s.make_particles();
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const Vec2 v = field(Vec2(ps.x[a], ps.y[a]));
    ps.vx[a] = v.x();
    ps.vy[a] = v.y();
  }
  SphEngine engine(s, ps);
  Eigen::Matrix2d virial = Eigen::Matrix2d::Zero();
  for (const auto& p : engine.pair_forces()) virial += p.f * p.d.transpose();
  const double scale = virial.cwiseAbs().maxCoeff();
  for (int c = 0; c < 4; ++c) {
    const auto [a, b] = component_index(kAll[c]);
    EXPECT_NEAR(t.at(kAll[c]).sum() * mesh.cell_area(), virial(a, b), 1e-12 * scale) << kAll[c];
  }
}

// v_x = s·y in the bulk. On the lattice, T_xy = −μ s Σ_ρ F(ρ) ρ_y² / (ε'² n*²) exactly (the bond weights of a
// lattice sum to 1 per unit area up to exp(−π² η²/ε'²)); its continuum limit is μ s, the Morris force with
// (μ_i + μ_j). Both quadratures must give the lattice value to 1e-9 (coarse stride 4: the R-sum of the
// Gaussian has aliasing error 2 exp(−π² η²/(4ε')²) ≈ 5e-10 at η' = 6 ε'); the lattice value must be μ s to
// the lattice error of the quintic at h = ε' (measured 1.6e-3; asserted 5e-3).
TEST(StressQuadratures, LinearShearGivesMuTimesShearRate) {
  const auto sc = channel(192, 1.0 / 32);
  const double mu = sc->phase_viscosity[0], rate = 0.7;
  const GaussianKernel k(sc->eta);
  const TensorMesh2D mesh = column_mesh(sc->box, sc->eta);
  const auto sampler = sampler_of(*sc, [&](const Vec2& p) { return Vec2(rate * (p.y() - 0.5), 0.0); });
  const SmoothingKernel w = sc->smoothing_kernel();
  double lattice_sum = 0.0;
  for (int a = -4; a <= 4; ++a)
    for (int b = -4; b <= 4; ++b) {
      const double r = sc->dx * std::hypot(a, b);
      if (r > 0 && r < w.support()) lattice_sum += w.dw(r) / r * (b * sc->dx) * (b * sc->dx);
    }
  const double n0 = sc->lattice_number_density();
  const double lattice = -mu * rate * lattice_sum / (sc->dx * sc->dx * n0 * n0);
  EXPECT_NEAR(lattice / (mu * rate), 1.0, 5e-3);
  ExactQuadrature exact;
  CoarseQuadrature coarse(0, 4);
  exact.setup(*sc, k, mesh, {"xy"});
  coarse.setup(*sc, k, mesh, {"xy"});
  const auto te = exact.evaluate(sampler).stress.at("xy"), tc = coarse.evaluate(sampler).stress.at("xy");
  int checked = 0;
  for (int n = 0; n < mesh.size(); ++n) {
    const double y = mesh.node(n).y();
    if (y < 0.35 || y > 0.65) continue;  // >= 8 η' from the walls, where v jumps to zero
    EXPECT_NEAR(te[n], lattice, 1e-9 * std::abs(lattice)) << y;
    EXPECT_NEAR(tc[n], lattice, 1e-9 * std::abs(lattice)) << y;
    ++checked;
  }
  EXPECT_GE(checked, 8);
  std::printf("linear shear: lattice T_xy / (mu s) = %.6f\n", lattice / (mu * rate));
}
