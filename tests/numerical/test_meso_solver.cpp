// The reduced model on the wall-free kolmogorov scene: with the Landweber closure of order n the steady
// amplitude must follow the Fourier prediction e / (1 − (1 − e)^{n+1}) of the true velocity (DESIGN.md §5),
// e = exp(−(2πkη'/L)²/4), to discretization error.
#include <gtest/gtest.h>

#include <cmath>

#include "core/scenes/analytic.hpp"
#include "core/averaging/averaging.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/closure/stress_quadrature.hpp"

using namespace closurelab;

namespace {

struct KolmogorovRun {
  double amplitude_ratio;  // steady sine amplitude of v̄ / (g / (ν κ²))
  double predicted;
  MesoResult result;
};

KolmogorovRun run_kolmogorov(int order, const std::string& quadrature, double spacing_over_eta) {
  const Registry& reg = builtin_registry();
  const int k = 2;
  const double eta = 1.0 / 16;
  const auto scene = reg.scenes.create(json{{"name", "kolmogorov"}, {"n_y", 64}, {"k", k}, {"eta_over_ly", eta}}, "/scene");
  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", eta}}, "/kernel");
  auto deconv = reg.deconvolvers.create(json{{"name", "landweber"}, {"order", order}}, "/deconvolver");
  auto quad = reg.quadratures.create(json{{"name", quadrature}}, "/quadrature");
  MesoSolverOptions opt;
  opt.spacing_over_eta = spacing_over_eta;
  opt.to_steady_state = false;
  opt.target_time = 0.15;  // the mode decays like exp(−ν κ² t), κ = 4π: e^{−24}
  auto integrator = builtin_registry().integrators.create(json{{"name", "explicit"}}, "/integrator");
  MesoSolver solver(*scene, *kernel, *deconv, *quad, *integrator, opt);
  KolmogorovRun out{0, 0, solver.run()};
  const double kw = 2 * M_PI * k;
  double s = 0, norm = 0;
  for (Eigen::Index i = 0; i < out.result.y.size(); ++i) {
    s += out.result.v[i] * std::sin(kw * out.result.y[i]);
    norm += std::sin(kw * out.result.y[i]) * std::sin(kw * out.result.y[i]);
  }
  out.amplitude_ratio = (s / norm) / (1.0 / (kw * kw));
  const double e = std::exp(-std::pow(kw * eta, 2) / 4);
  out.predicted = e / (1 - std::pow(1 - e, order + 1));
  return out;
}

}  // namespace

// The closure's part of the error is the same at every order to 1.7e-9 (measured; printed below), the SPH
// Laplacian's 1.04 % common to all: 1e-8 leaves a 6x margin.
constexpr double kOrderRatioTolerance = 1e-8;

TEST(ReducedModel, KolmogorovFollowsTheLandweberPrediction) {
  // The SPH viscous operator on the n_y = 64 lattice misses the continuum one by O((κ ε')²) ≈ 1 % at κ = 4π;
  // that factor is common to every order, so the ratios between orders test the closure alone.
  double first = 0.0;
  for (int n : {0, 1, 2, 5}) {
    const KolmogorovRun r = run_kolmogorov(n, "exact", 0.25);
    ASSERT_EQ(r.result.status, Status::target_time) << r.result.message;
    const double rel = r.amplitude_ratio / r.predicted;
    std::cout << "order " << n << ": amplitude ratio " << r.amplitude_ratio << ", predicted " << r.predicted
              << ", relative difference " << rel - 1 << "\n";
    EXPECT_NEAR(rel, 1.0, 0.015);  // measured 1.04 %
    if (n == 0) first = rel;
    std::printf("order %d: ratio to order 0's relative difference - 1 = %.3g\n", n, rel / first - 1.0);
    EXPECT_NEAR(rel / first, 1.0, kOrderRatioTolerance) << "order " << n;
  }
}

TEST(ReducedModel, StaggeredSchemeReachesASmoothSteadyStateInTheChannel) {
  // The collocated scheme (5.11)–(5.13) decouples odd and even nodes, and its one-sided boundary differences
  // excite that mode (measured: a ±0.25 checkerboard on a 0.05 profile); the conservative staggered variant
  // damps it. Assert: steady state reached, a profile that rises monotonically to the centre (no alternating
  // differences) and is symmetric about it.
  const Registry& reg = builtin_registry();
  const auto scene = reg.scenes.create(json{{"name", "poiseuille-uniform"}, {"n_y", 48}}, "/scene");
  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
  auto deconv = reg.deconvolvers.create(json{{"name", "landweber"}, {"order", 0}}, "/deconvolver");
  auto quad = reg.quadratures.create(json{{"name", "exact"}}, "/quadrature");
  MesoSolverOptions opt;
  opt.scheme = MesoScheme::staggered;
  auto integrator = builtin_registry().integrators.create(json{{"name", "explicit"}}, "/integrator");
  MesoSolver solver(*scene, *kernel, *deconv, *quad, *integrator, opt);
  const MesoResult r = solver.run();
  ASSERT_EQ(r.status, Status::converged) << r.message;
  const Eigen::Index n = r.v.size();
  for (Eigen::Index k = 0; k < n / 2; ++k) {
    EXPECT_GT(r.v[k + 1], r.v[k]) << "node " << k;
    EXPECT_NEAR(r.v[k], r.v[n - 1 - k], 1e-9 * r.v.maxCoeff()) << "node " << k;
  }
}

TEST(ReducedModel, WallConstraintMapEqualsTheDirectPairSweep) {
  // The solver applies the wall constraint forces as an affine map of the reconstruction on the rows next to
  // the walls (probed once). Check it against the definition, F_c(y_n) = −Σ_walls f_i^int ψ(y_n − q_i), from a
  // full pair sweep of the lattice carrying the reconstructed velocities; only rounding separates them.
  // Both wall models: the ghost-velocity wall's β depends on position only, so F_c stays affine in v.
  for (const char* walls : {"zero_velocity", "ghost_velocity"}) {
  SCOPED_TRACE(walls);
  const Registry& reg = builtin_registry();
  const auto scene = reg.scenes.create(json{{"name", "poiseuille-periodic"}, {"n_y", 48}, {"wall_model", walls}}, "/scene");
  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
  auto deconv = reg.deconvolvers.create(json{{"name", "landweber"}, {"order", 1}}, "/deconvolver");
  auto quad = reg.quadratures.create(json{{"name", "exact"}}, "/quadrature");
  MesoSolverOptions opt;
  opt.scheme = MesoScheme::staggered;
  opt.wall_constraint_forces = true;
  auto integrator = builtin_registry().integrators.create(json{{"name", "explicit"}}, "/integrator");
  MesoSolver solver(*scene, *kernel, *deconv, *quad, *integrator, opt);
  const Eigen::VectorXd y = solver.coarse_mesh().nodes();
  Eigen::VectorXd v(y.size());
  for (Eigen::Index n = 0; n < y.size(); ++n) v[n] = scene->analytic_vx(y[n]) * (1.0 + 0.3 * std::sin(7.0 * y[n]));
  solver.set_velocity(v);
  const Eigen::VectorXd mapped = solver.wall_constraint_force();

  ParticleSystem ps = scene->make_particles();
  std::vector<Vec2> fluid;
  for (std::size_t a = 0; a < ps.size(); ++a) fluid.emplace_back(ps.x[a], ps.y[a]);
  const Eigen::Matrix2Xd rec = solver.sample_reconstruction(fluid);  // zero in the walls
  for (std::size_t a = 0; a < ps.size(); ++a) ps.vx[a] = rec(0, static_cast<Eigen::Index>(a));
  SphEngine engine(*scene, ps);
  std::vector<double> net(ps.size(), 0.0);
  for (const PairForce& p : engine.pair_forces()) net[p.j] += p.f.x(), net[p.k] -= p.f.x();
  Eigen::VectorXd direct = Eigen::VectorXd::Zero(y.size());
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (!ps.fixed[a]) continue;
    double wx = 0.0;  // the column at x = 0 with its periodic images
    for (int k = -3; k <= 3; ++k) wx += kernel->factor(ps.x[a] + k * scene->box.lx);
    for (Eigen::Index n = 0; n < y.size(); ++n) direct[n] -= net[a] * wx * kernel->factor(y[n] - ps.y[a]);
  }
  ASSERT_GT(direct.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((mapped - direct).cwiseAbs().maxCoeff(), 1e-9 * direct.cwiseAbs().maxCoeff());
  }
}

TEST(ReducedModel, FirstOrderBeatsZeroOrderUnderThePeriodicForce) {
  // Paper Fig. 4: under the periodic force the first-order closure is more accurate than the zero-order one.
  // Checked against the Gaussian average of the analytic solution (D.3) at the coarse nodes (the quantity v̄
  // approximates), at n_y = 48 with the exact stress, staggered scheme and the wall constraint forces; the
  // coarse-coarse reconstruction is pinned to zero on the wall surfaces (without the pin, first order fails).
  // Measured max errors / analytic peak: 0.44 (zero order), 0.28 (first order); asserted: the ordering, with a
  // margin (first <= 0.8 x zero), and each below its measured value plus ~15 %.
  const Registry& reg = builtin_registry();
  const auto scene = reg.scenes.create(json{{"name", "poiseuille-periodic"}, {"n_y", 48}, {"n_x", 12}, {"eta_over_ly", 0.07}}, "/scene");
  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
  double err[2];
  for (int order : {0, 1}) {
    auto deconv = reg.deconvolvers.create(json{{"name", "landweber"}, {"order", order}}, "/deconvolver");
    auto quad = reg.quadratures.create(json{{"name", "exact"}}, "/quadrature");
    MesoSolverOptions opt;
    opt.scheme = MesoScheme::staggered;
    opt.wall_constraint_forces = true;
    auto integrator = builtin_registry().integrators.create(json{{"name", "explicit"}}, "/integrator");
    MesoSolver solver(*scene, *kernel, *deconv, *quad, *integrator, opt);
    const MesoResult r = solver.run();
    ASSERT_EQ(r.status, Status::converged) << r.message;
    double e = 0.0;
    for (Eigen::Index n = 1; n + 1 < r.y.size(); ++n) {
      const double avg = average_by_quadrature(scene->analytic_vx, [&](double t) { return kernel->factor(t); },
                                               kernel->support_radius(), r.y[n], scene->wall_lo, scene->wall_hi);
      e = std::max(e, std::abs(r.v[n] - avg) / scene->analytic_peak);
    }
    err[order] = e;
    std::cout << "order " << order << ": max error vs averaged analytic " << e << " (" << r.steps << " steps)\n";
  }
  EXPECT_LT(err[1], 0.8 * err[0]);
  EXPECT_LT(err[0], 0.5);   // guards against both getting worse together
  EXPECT_LT(err[1], 0.35);
}

TEST(ReducedModel, SetupIsIndependentOfTheStripWidth) {
  // The solver's lattice quantities (ρ̄, F̄ (2.14), the wall constraint map) are per unit length of an
  // x-invariant scene, so it builds them on the narrowest strip; a 12- and a 48-column scene must then give the
  // same coarse solution (the x-integrated coarse quadrature is width-independent too), to round-off. That the
  // strip's quantities equal the full lattice's is checked by NarrowestStripGivesTheSameAverages (ρ̄, F̄) and
  // WallConstraintMapEqualsTheDirectPairSweep (F_c against a sweep of the scene's full width).
  const Registry& reg = builtin_registry();
  Eigen::VectorXd v[2];
  int i = 0;
  for (int nx : {12, 48}) {
    const auto scene = reg.scenes.create(json{{"name", "poiseuille-periodic"}, {"n_y", 48}, {"n_x", nx}}, "/scene");
    const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
    auto deconv = reg.deconvolvers.create(json{{"name", "landweber"}, {"order", 1}}, "/deconvolver");
    auto quad = reg.quadratures.create(json{{"name", "coarse"}, {"stride_x", 0}, {"stride_y", 4}}, "/quadrature");
    MesoSolverOptions opt;
    opt.scheme = MesoScheme::staggered;
    opt.wall_constraint_forces = true;
    opt.to_steady_state = false;
    opt.target_time = 0.05;
    auto integrator = builtin_registry().integrators.create(json{{"name", "explicit"}}, "/integrator");
    MesoSolver solver(*scene, *kernel, *deconv, *quad, *integrator, opt);
    const MesoResult r = solver.run();
    ASSERT_EQ(r.status, Status::target_time) << r.message;
    v[i++] = r.v;
  }
  EXPECT_LT((v[0] - v[1]).cwiseAbs().maxCoeff(), 1e-10 * v[0].cwiseAbs().maxCoeff());
}

TEST(ReducedModel, NarrowestStripGivesTheSameAverages) {
  // The solver's setup uses Scene::narrowest_strip(): on an x-invariant lattice the averages with periodic
  // images in x are per unit length, so ρ̄ (2.8) and F̄ (2.14) on the narrow strip equal those of the 48-column
  // scene to round-off (the sums differ only in summation order).
  const Registry& reg = builtin_registry();
  const auto scene = reg.scenes.create(json{{"name", "poiseuille-periodic"}, {"n_y", 48}, {"n_x", 48}}, "/scene");
  const Scene strip = scene->narrowest_strip();
  ASSERT_LT(strip.nx, scene->nx);
  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
  const UniformMesh1D y_axis{scene->wall_lo, scene->eta, 9, false, 0.0};
  AveragingRequest req;
  req.external = true;
  const auto average = [&](const Scene& s) {
    const TensorMesh2D mesh{UniformMesh1D{0.0, s.box.lx, 1, true, s.box.lx}, y_axis};
    return average_particles(s.make_particles(), s.box, *kernel, mesh, req, {}, s.force_x);
  };
  const MesoFields wide = average(*scene), narrow = average(strip);
  EXPECT_LT((wide.rho - narrow.rho).cwiseAbs().maxCoeff(), 1e-12 * wide.rho.cwiseAbs().maxCoeff());
  EXPECT_LT((wide.fx - narrow.fx).cwiseAbs().maxCoeff(), 1e-12 * wide.fx.cwiseAbs().maxCoeff());
}
