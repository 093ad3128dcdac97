// The transport-velocity formulation (core/sph/transport_velocity.hpp) term by term: the pair terms against a hand
// computation, their antisymmetry, the engine's accelerations of two and three particles against the pair terms
// written out with the smoothing kernel's w and w', its step against PySPH's TransportVelocityStep written out, and
// the configuration's bad input (a background pressure <= 0, walls or solids, the schema's defaults).
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_run.hpp"
#include "core/sph/transport_velocity.hpp"
#include "tests/support/config_error.hpp"

using namespace closurelab;

namespace {

// a: n = 2, m = 1 (ρ = 2, V² = 1/4), p = 3, ν = 0.1 (η = 0.2), v = (1, 0), ṽ = (1.5, 0.5);
// b: n = 1, m = 1 (ρ = 1, V² = 1), p = 1, ν = 0.1 (η = 0.1), v = (0, 1), ṽ = (0.5, 2).
const TvfParticle kA = tvf_particle(2.0, 1.0, 3.0, 0.1, 1.0, 0.0, 1.5, 0.5);
const TvfParticle kB = tvf_particle(1.0, 1.0, 1.0, 0.1, 0.0, 1.0, 0.5, 2.0);

}  // namespace

// By hand, with F = w'/r = −2 and q = x_a − x_b = (1, 0.5): ∇_a W = F q = (−2, −1), V_a² + V_b² = 5/4, ε = 1/4,
// p_b = 4.
//   pressure:  p̄ = (ρ_b p_a + ρ_a p_b)/(ρ_a + ρ_b) = (3 + 2)/3 = 5/3;  −p̄ (5/4) ∇W = (25/6, 25/12)
//   viscosity: η_ab = 2 (0.2)(0.1)/0.3 = 2/15; x_ab·∇W = −2.5; r² + ε = 1.5; (5/4)(2/15)(−2.5)/1.5 = −5/18;
//              times v_ab = (1, −1): (−5/18, 5/18)
//   stress:    A_a = ρ_a v_a ⊗ (ṽ_a − v_a) = 2 (1, 0) ⊗ (0.5, 0.5) = [[1, 1], [0, 0]];
//              A_b = 1 (0, 1) ⊗ (0.5, 1) = [[0, 0], [0.5, 1]];
//              ½ (A_a + A_b)·∇W = ½ ((1)(−2) + (1)(−1), (0.5)(−2) + (1)(−1)) = (−1.5, −1); times 5/4: (−1.875, −1.25)
//   sum:       (25/6 − 5/18 − 15/8, 25/12 + 5/18 − 5/4) = (145/72, 10/9)
//   background: −p_b (5/4) ∇W = (10, 5)
TEST(TransportVelocity, PairTermsMatchAHandComputation) {
  double fx, fy, bx, by;
  tvf_pair_force(kA, kB, -2.0, 1.0, 0.5, 0.25, 4.0, fx, fy, bx, by);
  EXPECT_NEAR(fx, 145.0 / 72.0, 1e-14);
  EXPECT_NEAR(fy, 10.0 / 9.0, 1e-14);
  EXPECT_DOUBLE_EQ(bx, 10.0);
  EXPECT_DOUBLE_EQ(by, 5.0);
  // Each term alone: the pressure with the velocities and the stress zero, the viscous term with p = 0 and A = 0.
  const TvfParticle a0 = tvf_particle(2.0, 1.0, 3.0, 0.1, 0.0, 0.0, 0.0, 0.0),
                    b0 = tvf_particle(1.0, 1.0, 1.0, 0.1, 0.0, 0.0, 0.0, 0.0);
  tvf_pair_force(a0, b0, -2.0, 1.0, 0.5, 0.25, 4.0, fx, fy, bx, by);
  EXPECT_NEAR(fx, 25.0 / 6.0, 1e-14);
  EXPECT_NEAR(fy, 25.0 / 12.0, 1e-14);
  const TvfParticle av = tvf_particle(2.0, 1.0, 0.0, 0.1, 1.0, 0.0, 1.0, 0.0),
                    bv = tvf_particle(1.0, 1.0, 0.0, 0.1, 0.0, 1.0, 0.0, 1.0);
  tvf_pair_force(av, bv, -2.0, 1.0, 0.5, 0.25, 4.0, fx, fy, bx, by);
  EXPECT_NEAR(fx, -5.0 / 18.0, 1e-15);
  EXPECT_NEAR(fy, 5.0 / 18.0, 1e-15);
}

TEST(TransportVelocity, PairTermsAreAntisymmetric) {
  double fx, fy, bx, by, gx, gy, cx, cy;
  tvf_pair_force(kA, kB, -2.0, 1.0, 0.5, 0.25, 4.0, fx, fy, bx, by);
  tvf_pair_force(kB, kA, -2.0, -1.0, -0.5, 0.25, 4.0, gx, gy, cx, cy);
  EXPECT_NEAR(fx + gx, 0.0, 1e-14);
  EXPECT_NEAR(fy + gy, 0.0, 1e-14);
  EXPECT_EQ(bx, -cx);
  EXPECT_EQ(by, -cy);
}

namespace {

// A free (non-periodic) scene for a few particles: quintic spline, h = dx = 1, ρ0 = 1, μ = 0.05, c = 10.
Scene few_particle_scene() {
  Scene s;
  s.name = "few";
  s.box = PeriodicBox{100.0, 100.0, false, false};
  s.dx = 1.0;
  s.h = 1.0;
  s.rho0 = 1.0;
  s.phase_viscosity = {0.05};
  s.sound_speed = 10.0;
  s.analytic_peak = 1.0;
  s.x_invariant = false;
  s.body_force = [](double, double) { return Vec2(0.0, 0.0); };
  return s;
}

}  // namespace

// Two particles at rest 1.2 h apart along x, mass m: n = W(0) + W(r) for both, p = c² (m n − ρ0), p̄ = p, and
// v = ṽ = 0, so only the pressure acts: a_0 = −p (2/n²) w'(r) (x_0 − x_1)/r / m, and â_0 − a_0 = −p_b (2/n²) w'(r)
// (x_0 − x_1)/r / m with p_b = ρ0 c².
TEST(TransportVelocity, TwoParticlesAtRestFeelThePressureAndTheBackgroundPressure) {
  const Scene s = few_particle_scene();
  ParticleSystem ps;
  const double m = 1.3;
  ps.add(10.0, 10.0, m, 0, false);
  ps.add(11.2, 10.0, m, 0, false);
  SphEngine engine(s, ps, SphEngineOptions{SphFormulation::transport_velocity, 1.0});
  engine.compute_accelerations();
  const SmoothingKernel w = s.smoothing_kernel();
  const double r = 1.2, n = w.w(0.0) + w.w(r), p = 100.0 * (m * n - 1.0), grad_x = w.dw(r) * (-1.2) / r;
  EXPECT_NEAR(engine.number_density()[0], n, 1e-14);
  const double a0 = -p * (2.0 / (n * n)) * grad_x / m, b0 = -100.0 * (2.0 / (n * n)) * grad_x / m;
  EXPECT_NEAR(engine.ax()[0], a0, 1e-12 * std::abs(a0));
  EXPECT_NEAR(engine.ax()[1], -a0, 1e-12 * std::abs(a0));
  EXPECT_NEAR(engine.background_ax()[0], b0, 1e-12 * std::abs(b0));
  EXPECT_NEAR(engine.background_ax()[1], -b0, 1e-12 * std::abs(b0));
  EXPECT_EQ(engine.ay()[0], 0.0);
  EXPECT_EQ(engine.background_ay()[0], 0.0);
}

// Three moving particles in a triangle with velocities: the engine's accelerations are the sums of the pair terms
// over the pairs, with ∇W from the kernel's w'(r) and ε = 0.01 h²; and one step is PySPH's TransportVelocityStep:
// v ← v + ½Δt a, ṽ = v + ½Δt â, x ← x + Δt ṽ, evaluate, v ← v + ½Δt a.
TEST(TransportVelocity, ThreeParticlesSumThePairTermsAndStepAsPySph) {
  const Scene s = few_particle_scene();
  ParticleSystem ps;
  const double m = 0.9;
  const double x[3] = {10.0, 11.1, 10.4}, y[3] = {10.0, 10.2, 10.9}, u[3] = {0.3, -0.2, 0.1}, v[3] = {0.0, 0.4, -0.5};
  for (int a = 0; a < 3; ++a) {
    ps.add(x[a], y[a], m, 0, false);
    ps.vx[a] = u[a];
    ps.vy[a] = v[a];
  }
  ParticleSystem start = ps;
  SphEngine engine(s, ps, SphEngineOptions{SphFormulation::transport_velocity, 0.5});
  engine.compute_accelerations();
  const SmoothingKernel w = s.smoothing_kernel();
  double n[3];
  for (int a = 0; a < 3; ++a) {
    n[a] = w.w(0.0);
    for (int b = 0; b < 3; ++b)
      if (b != a) n[a] += w.w(std::hypot(x[a] - x[b], y[a] - y[b]));
  }
  const double nu = 0.05, pb = 0.5 * 100.0, eps = 0.01;
  // At the first evaluation ṽ = v: no extra stress.
  TvfParticle in[3];
  for (int a = 0; a < 3; ++a) in[a] = tvf_particle(n[a], m, 100.0 * (m * n[a] - 1.0), nu, u[a], v[a], u[a], v[a]);
  for (int a = 0; a < 3; ++a) {
    double ax = 0.0, ay = 0.0, bx = 0.0, by = 0.0;
    for (int b = 0; b < 3; ++b) {
      if (b == a) continue;
      const double qx = x[a] - x[b], qy = y[a] - y[b], r = std::hypot(qx, qy);
      double fx, fy, gx, gy;
      tvf_pair_force(in[a], in[b], w.dw(r) / r, qx, qy, eps, pb, fx, fy, gx, gy);
      ax += fx, ay += fy, bx += gx, by += gy;
    }
    const double scale = std::hypot(ax, ay) / m;
    EXPECT_NEAR(engine.ax()[a], ax / m, 1e-12 * scale) << a;
    EXPECT_NEAR(engine.ay()[a], ay / m, 1e-12 * scale) << a;
    EXPECT_NEAR(engine.background_ax()[a], bx / m, 1e-12 * std::hypot(bx, by) / m) << a;
    EXPECT_NEAR(engine.background_ay()[a], by / m, 1e-12 * std::hypot(bx, by) / m) << a;
  }
  // The step: the stage-1 state from the engine's own accelerations, written out.
  const double dt = 1e-3;
  std::vector<double> ax0 = engine.ax(), ay0 = engine.ay(), bx0 = engine.background_ax(), by0 = engine.background_ay();
  engine.step(dt);
  for (int a = 0; a < 3; ++a) {
    const double uh = start.vx[a] + 0.5 * dt * ax0[a], vh = start.vy[a] + 0.5 * dt * ay0[a];
    const double ut = uh + 0.5 * dt * bx0[a], vt = vh + 0.5 * dt * by0[a];
    EXPECT_DOUBLE_EQ(engine.transport_vx()[a], ut);
    EXPECT_DOUBLE_EQ(engine.transport_vy()[a], vt);
    EXPECT_DOUBLE_EQ(ps.x[a], start.x[a] + dt * ut);
    EXPECT_DOUBLE_EQ(ps.y[a], start.y[a] + dt * vt);
    EXPECT_DOUBLE_EQ(ps.vx[a], uh + 0.5 * dt * engine.ax()[a]);
    EXPECT_DOUBLE_EQ(ps.vy[a], vh + 0.5 * dt * engine.ay()[a]);
  }
}

TEST(TransportVelocity, SolverSchemaDefaultsToTheStandardFormulation) {
  const SphRunOptions d, r = sph_run_options_from(resolve_params(json::object(), sph_solver_schema(), "/solver"));
  EXPECT_EQ(d.engine.formulation, SphFormulation::standard);
  EXPECT_EQ(r.engine.formulation, d.engine.formulation);
  EXPECT_EQ(r.engine.transport_background_pressure_factor, d.engine.transport_background_pressure_factor);
  // A stored section from before the parameters existed reads as the standard formulation.
  const json old = {{"kappa", 0.25}};
  EXPECT_EQ(upgraded_sph_solver_params(old).at("formulation"), "standard");
}

TEST(TransportVelocity, ABackgroundPressureAtOrBelowZeroIsAConfigErrorAtItsPath) {
  for (double bad : {0.0, -1.0}) {
    try {
      resolve_params({{"formulation", "transport_velocity"}, {"transport_background_pressure_factor", bad}},
                     sph_solver_schema(), "/cells/0/solver");
      FAIL() << "accepted " << bad;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.path(), "/cells/0/solver/transport_background_pressure_factor") << e.what();
    }
  }
  EXPECT_NE(test_support::config_error([] {
              resolve_params({{"formulation", "transport"}}, sph_solver_schema(), "/solver");
            }).find("/solver/formulation"),
            std::string::npos);
}

// Refused at validation, at the solver's formulation: ghost-velocity walls under the transport velocity (it has its
// own wall condition), and the standard formulation on the cavity (its scene needs the transport velocity). Walls
// at zero velocity and the periodic Taylor–Green box are accepted.
TEST(TransportVelocity, GhostWallsAndTheStandardCavityAreRefusedAtTheFormulation) {
  const json tvf = resolve_params({{"formulation", "transport_velocity"}, {"mode", "target_time"}, {"target_time", 0.01}},
                                  sph_solver_schema(), "/solver");
  const json standard = resolve_params({{"mode", "target_time"}, {"target_time", 0.01}}, sph_solver_schema(), "/solver");
  const auto ghost = builtin_registry().scenes.create(
      {{"name", "poiseuille-uniform"}, {"n_y", 32}, {"wall_model", "ghost_velocity"}}, "/scene");
  const auto cavity = builtin_registry().scenes.create({{"name", "lid-driven-cavity"}, {"n", 20}}, "/scene");
  for (const auto& [scene, solver] : {std::pair{ghost.get(), &tvf}, std::pair{cavity.get(), &standard}}) {
    try {
      check_direct_run(*scene, *solver, "/solver");
      FAIL() << scene->name << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.path(), "/solver/formulation") << e.what();
    }
  }
  ParticleSystem ps = ghost->make_particles();
  EXPECT_THROW(SphEngine(*ghost, ps, SphEngineOptions{SphFormulation::transport_velocity, 1.0}), std::invalid_argument);
  const auto channel = builtin_registry().scenes.create({{"name", "poiseuille-uniform"}, {"n_y", 32}}, "/scene");
  const auto tg = builtin_registry().scenes.create({{"name", "taylor-green"}, {"n", 32}}, "/scene");
  EXPECT_NO_THROW(check_direct_run(*channel, tvf, "/solver"));
  EXPECT_NO_THROW(check_direct_run(*tg, tvf, "/solver"));
  EXPECT_NO_THROW(check_direct_run(*cavity, tvf, "/solver"));
}

// The cavity scene is PySPH's cavity.py: n² fluid particles on (w + (i + ½) dx) inside walls as thick as the
// support plus a layer, the solid particles above the fluid (corners included) moving at the lid speed, the others
// at rest; m = ρ0 dx², ν = U L/Re, c = 10 U.
TEST(TransportVelocity, CavitySceneIsPySphs) {
  const auto s = builtin_registry().scenes.create({{"name", "lid-driven-cavity"}, {"n", 20}}, "/scene");
  const ParticleSystem ps = s->make_particles();
  const double dx = 0.05, w = s->cavity->origin;
  EXPECT_DOUBLE_EQ(w, 4 * dx);  // quintic, h = dx: support 3 dx, plus one layer
  std::size_t fluid = 0, lid = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    EXPECT_DOUBLE_EQ(ps.mass[a], dx * dx);
    const bool inside = ps.x[a] > w && ps.x[a] < w + 1.0 && ps.y[a] > w && ps.y[a] < w + 1.0;
    EXPECT_EQ(ps.fixed[a] == 0, inside);
    fluid += inside;
    const bool top = ps.y[a] > w + 1.0;
    lid += top;
    EXPECT_EQ(ps.vx[a], top ? 1.0 : 0.0);
    EXPECT_EQ(ps.vy[a], 0.0);
  }
  EXPECT_EQ(fluid, 400u);
  EXPECT_EQ(lid, 4u * 28u);
  EXPECT_NEAR(s->phase_viscosity[0], 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(s->sound_speed, 10.0);
}

// The scene: the exact field at t = 0 on the particles (PySPH's exact_solution), ν = U L/Re, c = 10 U, m = ρ0 dx²,
// and b = −8π²/Re at L = U = 1.
TEST(TransportVelocity, TaylorGreenSceneIsPySphs) {
  const auto s = builtin_registry().scenes.create({{"name", "taylor-green"}, {"n", 40}}, "/scene");
  ASSERT_TRUE(s->taylor_green.has_value());
  EXPECT_DOUBLE_EQ(s->phase_viscosity[0], 0.01);
  EXPECT_DOUBLE_EQ(s->sound_speed, 10.0);
  EXPECT_DOUBLE_EQ(s->particle_mass(), 1.0 / 1600.0);
  EXPECT_NEAR(s->taylor_green->decay_rate, 8.0 * M_PI * M_PI / 100.0, 1e-15);
  EXPECT_EQ(s->background_pressure, 0.0);
  const ParticleSystem ps = s->make_particles();
  ASSERT_EQ(ps.size(), 1600u);
  for (std::size_t a : {0ul, 17ul, 999ul}) {
    EXPECT_DOUBLE_EQ(ps.vx[a], -std::cos(2 * M_PI * ps.x[a]) * std::sin(2 * M_PI * ps.y[a]));
    EXPECT_DOUBLE_EQ(ps.vy[a], std::sin(2 * M_PI * ps.x[a]) * std::cos(2 * M_PI * ps.y[a]));
    EXPECT_FALSE(ps.fixed[a]);
  }
  // The exact pressure p = −¼ ρ U² e^{2bt} (cos 4πx + cos 4πy); the vortex is also the cellular mode shifted by
  // L/4 (the 2D reduced model's exact solution), so the time unit is its decay time 1/(2k²ν) = Re/(8π²).
  EXPECT_NEAR(s->taylor_green->pressure_at(0.0, 0.0, 0.0), -0.5, 1e-15);
  EXPECT_NEAR(s->time_scale(), 100.0 / (8.0 * M_PI * M_PI), 1e-14);
  ASSERT_TRUE(s->cellular_mode.has_value());
  for (const Vec2& p : {Vec2(0.1, 0.7), Vec2(0.33, 0.21), Vec2(0.9, 0.05)}) {
    const double k = s->cellular_mode->wavenumber, o = s->cellular_mode->offset;
    const Vec2 mode(std::sin(k * (p.x() + o)) * std::cos(k * (p.y() + o)), -std::cos(k * (p.x() + o)) * std::sin(k * (p.y() + o)));
    const Vec2 v = s->taylor_green->velocity_at(p.x(), p.y(), 0.3);
    EXPECT_NEAR(v.x(), s->cellular_mode->amplitude(0.3) * mode.x(), 1e-14);
    EXPECT_NEAR(v.y(), s->cellular_mode->amplitude(0.3) * mode.y(), 1e-14);
  }
  EXPECT_NE(test_support::config_error([] {
              builtin_registry().scenes.create({{"name", "taylor-green"}, {"re", 0.0}}, "/scene");
            }).find("/scene/re"),
            std::string::npos);
}
