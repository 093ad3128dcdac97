// The cellular-flow scene: its exact field against the equations it claims to solve (finite differences), the
// Gaussian average of the mode against a 2D GSL quadrature, the scene's declaration (force, start, bad input), and
// the experiment kinds that need an x-invariant scene refusing it.
#include <gtest/gtest.h>
#include <gsl/gsl_integration.h>

#include <cmath>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/scenes/analytic.hpp"
#include "core/sph/scene.hpp"
#include "experiments/kinds/experiment_kind.hpp"

using namespace closurelab;

namespace {

std::unique_ptr<Scene> cellular(json p) {
  p["name"] = "cellular";
  return builtin_registry().scenes.create(p, "/scene");
}

// Sample points inside the box (not on symmetry lines of the mode).
const double kPoints[][2] = {{0.13, 0.71}, {0.42, 0.07}, {0.88, 0.33}, {0.57, 0.94}};

// Central differences with step s: truncation s² f'''/6 relative to f' ~ (k s)²/6 = 6.6e-6 for k = 4π, s = 1e-3;
// round-off ~ 1e-16 / s² = 1e-10 in the second differences. Tolerances below are 1e-4 of the terms' size.
constexpr double kStep = 1e-3;

Vec2 velocity(const Scene& s, double x, double y) {
  return s.cellular_mode->steady_amplitude * cellular_mode(x, y, s.cellular_mode->wavenumber);
}

}  // namespace

TEST(CellularScene, ModeIsDivergenceFree) {
  const double k = 4.0 * M_PI;
  for (const auto& p : kPoints) {
    const double x = p[0], y = p[1], s = kStep;
    const double div = (cellular_mode(x + s, y, k).x() - cellular_mode(x - s, y, k).x()) / (2 * s) +
                       (cellular_mode(x, y + s, k).y() - cellular_mode(x, y - s, k).y()) / (2 * s);
    EXPECT_NEAR(div, 0.0, 1e-4 * k);  // each term is up to k in size
  }
}

TEST(CellularScene, SteadyVelocityBalancesForceAndViscosity) {
  // ν Δv + F = 0 for the scene's steady velocity and body force (m = 2 cells, ν = 0.5).
  const auto sc = cellular({{"m", 2}, {"mu", 0.5}, {"re", 0.05}, {"n", 32}});
  const double nu = 0.5, s = kStep, k = sc->cellular_mode->wavenumber;
  EXPECT_DOUBLE_EQ(k, 4.0 * M_PI);
  EXPECT_DOUBLE_EQ(sc->cellular_mode->steady_amplitude, 0.05 * k * nu);  // Re = A / (k ν)
  for (const auto& p : kPoints) {
    const double x = p[0], y = p[1];
    const Vec2 lap = (velocity(*sc, x + s, y) + velocity(*sc, x - s, y) + velocity(*sc, x, y + s) +
                      velocity(*sc, x, y - s) - 4.0 * velocity(*sc, x, y)) / (s * s);
    const Vec2 f = sc->body_force(x, y);
    const double size = 2.0 * k * k * nu * sc->cellular_mode->steady_amplitude;  // |ν Δv| at most
    EXPECT_NEAR(nu * lap.x() + f.x(), 0.0, 1e-4 * size);
    EXPECT_NEAR(nu * lap.y() + f.y(), 0.0, 1e-4 * size);
  }
}

TEST(CellularScene, PressureBalancesTheInertialTerm) {
  // ρ (v·∇)v + ∇p = 0: the steady velocity solves the full Navier–Stokes equations with that pressure.
  const double k = 2.0 * M_PI, rho = 1.3, a = 0.7, s = kStep;
  const auto v = [&](double x, double y) { return Vec2(a * cellular_mode(x, y, k)); };
  for (const auto& p : kPoints) {
    const double x = p[0], y = p[1];
    const Vec2 dvdx = (v(x + s, y) - v(x - s, y)) / (2 * s), dvdy = (v(x, y + s) - v(x, y - s)) / (2 * s);
    const Vec2 adv = rho * (v(x, y).x() * dvdx + v(x, y).y() * dvdy);
    const Vec2 grad_p((cellular_pressure(x + s, y, k, rho, a) - cellular_pressure(x - s, y, k, rho, a)) / (2 * s),
                      (cellular_pressure(x, y + s, k, rho, a) - cellular_pressure(x, y - s, k, rho, a)) / (2 * s));
    const double size = rho * a * a * k;
    EXPECT_NEAR(adv.x() + grad_p.x(), 0.0, 1e-4 * size);
    EXPECT_NEAR(adv.y() + grad_p.y(), 0.0, 1e-4 * size);
  }
}

TEST(CellularScene, GaussianAverageOfTheModeIsItsFourierFactor) {
  // ∫∫ ψ_η(r) φ(q − r) d²r by nested GSL quadrature (relative 1e-11) against exp(−|k|² η² / 4), |k|² = 2k², and
  // the kernel's own symbol. L = 1, m = 3, η = 1/16: factor exp(−2 (6π)² / 1024) = 0.50 (a real reduction).
  const auto kernel = builtin_registry().kernels.create(json{{"name", "gaussian"}, {"eta", 1.0 / 16.0}}, "/kernel");
  const double k = 6.0 * M_PI, eta = 1.0 / 16.0, radius = kernel->support_radius();
  const double expected = std::exp(-2.0 * k * k * eta * eta / 4.0);
  EXPECT_NEAR(kernel->symbol(Vec2(k, k) / (2.0 * M_PI)), expected, 1e-13);
  struct Ctx {
    const AveragingKernel* w;
    double k, x, y, rx;
    int component;
  };
  gsl_integration_workspace* outer_ws = gsl_integration_workspace_alloc(200);
  gsl_integration_workspace* inner_ws = gsl_integration_workspace_alloc(200);
  for (const auto& p : kPoints) {
    for (int component = 0; component < 2; ++component) {
      Ctx c{kernel.get(), k, p[0], p[1], 0.0, component};
      gsl_function inner;
      inner.params = &c;
      inner.function = [](double ry, void* v) {
        const Ctx& q = *static_cast<Ctx*>(v);
        return q.w->value(Vec2(q.rx, ry)) * cellular_mode(q.x - q.rx, q.y - ry, q.k)[q.component];
      };
      gsl_function outer;
      struct Both {
        Ctx* c;
        gsl_function* inner;
        gsl_integration_workspace* ws;
        double radius;
      } both{&c, &inner, inner_ws, radius};
      outer.params = &both;
      outer.function = [](double rx, void* v) {
        Both& b = *static_cast<Both*>(v);
        b.c->rx = rx;
        double r = 0.0, e = 0.0;
        gsl_integration_qag(b.inner, -b.radius, b.radius, 1e-14, 1e-11, 200, GSL_INTEG_GAUSS41, b.ws, &r, &e);
        return r;
      };
      double avg = 0.0, err = 0.0;
      gsl_integration_qag(&outer, -radius, radius, 1e-14, 1e-11, 200, GSL_INTEG_GAUSS41, outer_ws, &avg, &err);
      EXPECT_NEAR(avg, expected * cellular_mode(p[0], p[1], k)[component], 1e-9);
    }
  }
  gsl_integration_workspace_free(inner_ws);
  gsl_integration_workspace_free(outer_ws);
}

TEST(CellularScene, DeclaresForceStartAndExactAmplitude) {
  const auto forced = cellular({{"n", 16}, {"re", 0.02}});
  const Scene::CellularMode& mode = *forced->cellular_mode;
  const double k = 2.0 * M_PI, a = 0.02 * k;  // L = 1, ν = 1
  EXPECT_FALSE(forced->x_invariant);
  EXPECT_DOUBLE_EQ(mode.decay_rate, 2.0 * k * k);
  EXPECT_DOUBLE_EQ(mode.initial_amplitude, 0.0);
  EXPECT_NEAR(mode.amplitude(1.0 / mode.decay_rate), a * (1.0 - std::exp(-1.0)), 1e-15);
  const Vec2 f = forced->body_force(0.1, 0.3);
  EXPECT_NEAR(f.x(), 2.0 * k * k * a * std::sin(0.1 * k) * std::cos(0.3 * k), 1e-12);
  EXPECT_NEAR(f.y(), -2.0 * k * k * a * std::cos(0.1 * k) * std::sin(0.3 * k), 1e-12);
  for (double v : forced->make_particles().vx) EXPECT_EQ(v, 0.0);

  const auto decaying = cellular({{"n", 16}, {"re", 0.02}, {"forced", false}, {"initial", "taylor_green"}});
  EXPECT_EQ(decaying->body_force(0.1, 0.3), Vec2(0.0, 0.0));
  EXPECT_NEAR(decaying->cellular_mode->amplitude(0.01), a * std::exp(-2.0 * k * k * 0.01), 1e-15);
  const ParticleSystem ps = decaying->make_particles();
  ASSERT_EQ(ps.size(), 256u);
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const Vec2 v = a * cellular_mode(ps.x[p], ps.y[p], k);
    EXPECT_DOUBLE_EQ(ps.vx[p], v.x());
    EXPECT_DOUBLE_EQ(ps.vy[p], v.y());
  }
}

TEST(CellularScene, BadInputNamesTheParameter) {
  const auto path_of = [](const json& p) {
    try {
      cellular(p);
    } catch (const ConfigError& e) {
      return e.path();
    }
    return std::string("no error");
  };
  EXPECT_EQ(path_of({{"forced", false}}), "/scene/initial");  // nothing would ever move
  EXPECT_EQ(path_of({{"n", 16}, {"m", 4}}), "/scene/n");       // fewer than 8 particles per cell
  EXPECT_EQ(path_of({{"eta_over_l", 0.2}}), "/scene/eta_over_l");
  EXPECT_EQ(path_of({{"re", 0.0}}), "/scene/re");
}

TEST(CellularScene, KindsThatNeedAnXInvariantSceneRefuseIt) {
  const json cell = {{"scene", {{"name", "cellular"}, {"n", 16}}}};
  const auto refused_at = [&](const std::string& kind, const json& more = json::object()) {
    json c = cell;
    c.update(more);
    try {
      builtin_registry().experiments.get(kind, "/kind").resolve(c, "", builtin_registry());
    } catch (const ConfigError& e) {
      return e.path();
    }
    return std::string("accepted");
  };
  // reduced_model serves the cellular scene by its 2D model; its 1D column refuses it.
  EXPECT_EQ(refused_at("reduced_model", {{"model", "column"}}), "/scene");
  EXPECT_EQ(refused_at("quadrature_convergence"), "/scene");
  EXPECT_EQ(refused_at("direct_sph_validation"), "accepted");
}
