// The two-phase layered channel (§7): the van der Waals EOS (7.1) and its parametrization, the analytic
// piecewise-parabolic steady solution against independent quadrature and the ODE, and a short direct SPH run.
#include <gtest/gtest.h>

#include <gsl/gsl_integration.h>

#include <cmath>

#include "core/scenes/analytic.hpp"
#include "core/sph/equation_of_state.hpp"
#include "core/base/gsl_support.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_run.hpp"

using namespace closurelab;

namespace {

std::unique_ptr<Scene> layered(json p) {
  p["name"] = "layered-two-phase";
  return builtin_registry().scenes.create(p, "/scene");
}

// ∫_a^b f by GSL adaptive quadrature, split at `breaks` (independent of the closed form).
double integrate(const std::function<double(double)>& f, double a, double b, std::vector<double> breaks) {
  gsl_errors_as_status();
  gsl_function F;
  F.function = [](double t, void* p) { return (*static_cast<const std::function<double(double)>*>(p))(t); };
  F.params = const_cast<std::function<double(double)>*>(&f);
  std::vector<double> e{a};
  for (double t : breaks)
    if (t > a && t < b) e.push_back(t);
  e.push_back(b);
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(1000);
  double total = 0.0;
  for (std::size_t k = 0; k + 1 < e.size(); ++k) {
    double r = 0.0, err = 0.0;
    gsl_integration_qags(&F, e[k], e[k + 1], 0.0, 1e-13, 1000, w, &r, &err);
    total += r;
  }
  gsl_integration_workspace_free(w);
  return total;
}

}  // namespace

TEST(VanDerWaalsEos, DerivativeAndSoundSpeedAgainstFiniteDifferences) {
  const double n0 = 3.7e4, m = 1.0 / n0, c = 6.5e-3;
  for (const auto& [phi, a] : std::vector<std::pair<double, double>>{{0.5, 1.0}, {0.3, 0.9}, {0.7, 3.0}, {0.5, 0.0}}) {
    const VanDerWaalsEos e = VanDerWaalsEos::from_liquid(n0, m, c, phi, a, 0.5, "/scene");
    EXPECT_NEAR(e.c1 * n0, phi, 1e-14);
    EXPECT_NEAR(e.c2 * n0, a * e.kt, 1e-14 * e.kt);
    for (double k : {1.0, 0.5}) {
      for (double x : {0.8, 1.0, 1.1}) {
        const double n = x * n0, h = 1e-5 * n0;
        const double fd = (e.pressure(n + h, k) - e.pressure(n - h, k)) / (2.0 * h);  // O(h²) ≈ 1e-10 relative
        EXPECT_NEAR(e.dpressure_dn(n, k), fd, 1e-8 * std::abs(fd) + 1e-12 * e.kt) << phi << " " << a << " " << x;
      }
    }
    // The sound speed at n0: c² = dP/dρ = (1/m) dP/dn (like pairs), by finite differences in ρ = m n.
    const double h = 1e-6 * n0;
    const double dp_drho = (e.pressure(n0 + h, 1.0) - e.pressure(n0 - h, 1.0)) / (2.0 * h * m);
    EXPECT_NEAR(std::sqrt(dp_drho), c, 1e-9 * c);
    // A stable liquid at rest: P(n0) > 0 and dP/dn(n0) > 0.
    EXPECT_GT(e.pressure(n0, 1.0), 0.0);
    EXPECT_GT(e.dpressure_dn(n0, 1.0), 0.0);
    // Unlike pairs: P/n² rises by (1 − k*) c_2 at any density, and the jump at n0 is (1 − k*) c_2 n0².
    EXPECT_NEAR((e.pressure(1.05 * n0, 0.5) - e.pressure(1.05 * n0, 1.0)) / std::pow(1.05 * n0, 2),
                e.unlike_excess_over_n2(), 1e-12 * e.kt / n0 + 1e-12 * e.c2);
    EXPECT_NEAR(e.interface_pressure_jump(n0), 0.5 * a * n0 * e.kt, 1e-12 * n0 * e.kt);
  }
  // Defaults φ = 1/2, a = 1: P(n0) = ρ0 c²/2, jump (1 − k*) ρ0 c²/2; P > 0 and dP/dn > 0 for 0 < n < 2 n0.
  const VanDerWaalsEos e = VanDerWaalsEos::from_liquid(n0, m, c, 0.5, 1.0, 0.5, "");
  EXPECT_NEAR(e.pressure(n0, 1.0), 0.5 * c * c, 1e-12 * c * c);
  EXPECT_NEAR(e.interface_pressure_jump(n0), 0.25 * c * c, 1e-12 * c * c);
  for (int k = 1; k < 200; ++k) {
    const double n = k / 100.0 * n0;
    ASSERT_GT(e.pressure(n, 1.0), 0.0) << n / n0;
    ASSERT_GT(e.dpressure_dn(n, 1.0), 0.0) << n / n0;
  }
  // At the admissible limit a → a_max the liquid loses P > 0 or dP/dn > 0.
  EXPECT_THROW(VanDerWaalsEos::from_liquid(n0, m, c, 0.3, VanDerWaalsEos::a_max(0.3), 0.5, ""), ConfigError);
  EXPECT_NEAR(VanDerWaalsEos::a_max(0.3), 1.0 / (2.0 * 0.49), 1e-15);  // dP/dn binds for φ < 1/2
  EXPECT_NEAR(VanDerWaalsEos::a_max(0.7), 1.0 / 0.3, 1e-14);           // P > 0 binds for φ > 1/2
}

TEST(LayeredAnalytic, MatchesIndependentQuadratureAndTheOde) {
  const double l1 = 0.2, l2 = 1.2, rho = 1.3, g = 0.7;
  const std::vector<double> faces{0.3, 0.35, 0.6, 0.9, 1.0};
  const std::vector<double> mus{200, 100, 200, 50, 200, 100};
  const LayeredChannelFlow flow(l1, l2, faces, mus, rho, g);
  const auto mu = [&](double s) { return flow.viscosity(s); };
  // C from v(l2) = 0 by quadrature: C ∫ 1/μ = ρg ∫ (s − l1)/μ.
  const double C = rho * g * integrate([&](double s) { return (s - l1) / mu(s); }, l1, l2, faces) /
                   integrate([&](double s) { return 1.0 / mu(s); }, l1, l2, faces);
  double vmax = 0.0;
  for (int k = 1; k < 100; ++k) {
    const double y = l1 + (l2 - l1) * k / 100.0;
    const double v = integrate([&](double s) { return (C - rho * g * (s - l1)) / mu(s); }, l1, y, faces);
    EXPECT_NEAR(flow.velocity(y), v, 1e-12 * flow.peak()) << y;
    vmax = std::max(vmax, v);
  }
  EXPECT_NEAR(flow.peak(), vmax, 1e-3 * vmax);  // the sampled maximum lies within the grid's reach of the peak
  EXPECT_GE(flow.peak(), vmax * (1.0 - 1e-14));
  EXPECT_EQ(flow.velocity(l1), 0.0);
  EXPECT_EQ(flow.velocity(l2), 0.0);
  EXPECT_NEAR(flow.velocity(l2 - 1e-12), 0.0, 1e-9 * flow.peak());
  // The ODE inside each layer: (μ v')' = −ρg (a parabola: the second difference is exact up to round-off),
  // and the shear stress μ v' is continuous across the interfaces (one-sided differences).
  const double h = 1e-4;
  for (int k = 0; k < 200; ++k) {
    const double y = l1 + 2 * h + (l2 - l1 - 4 * h) * k / 199.0;
    bool near_face = false;
    for (double f : faces) near_face = near_face || std::abs(y - f) < 1.5 * h;
    if (near_face) continue;
    const double d2 = (flow.velocity(y + h) - 2.0 * flow.velocity(y) + flow.velocity(y - h)) / (h * h);
    EXPECT_NEAR(mu(y) * d2, -rho * g, 1e-5 * rho * g) << y;
  }
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const double f = faces[k];
    const double below = mus[k] * (3.0 * flow.velocity(f) - 4.0 * flow.velocity(f - h) + flow.velocity(f - 2 * h)) / (2 * h);
    const double above = mus[k + 1] * (-3.0 * flow.velocity(f) + 4.0 * flow.velocity(f + h) - flow.velocity(f + 2 * h)) / (2 * h);
    EXPECT_NEAR(below, above, 1e-6 * rho * g * (l2 - l1)) << f;
    EXPECT_NEAR(below, flow.shear_stress(f), 1e-6 * rho * g * (l2 - l1)) << f;
  }
}

TEST(LayeredAnalytic, WithoutLayersItIsPoiseuille515) {
  const double l1 = 0.1875, l2 = 1.1875, rho = 1.0, g = 1.0, mu = 200.0;
  const LayeredChannelFlow plain(l1, l2, {}, {mu}, rho, g);
  const LayeredChannelFlow same(l1, l2, {0.4, 0.5, 0.9}, {mu, mu, mu, mu}, rho, g);  // layers of the same fluid
  for (int k = 0; k <= 100; ++k) {
    const double y = l1 - 0.05 + (l2 - l1 + 0.1) * k / 100.0;
    const double p = poiseuille_velocity(y, l1, l2, rho, g, mu);
    EXPECT_NEAR(plain.velocity(y), p, 1e-14 * rho * g / mu) << y;
    EXPECT_NEAR(same.velocity(y), p, 1e-14 * rho * g / mu) << y;
  }
  EXPECT_NEAR(plain.peak(), rho * g * (l2 - l1) * (l2 - l1) / (8.0 * mu), 1e-16);
  EXPECT_NEAR(plain.peak_height(), 0.5 * (l1 + l2), 1e-15);
  // The scene's analytic solution is this one with its interfaces.
  const auto s = layered(json{{"case", "case3"}});
  std::vector<double> mus{200};
  for (std::size_t k = 0; k < s->interfaces.size(); ++k) mus.push_back(k % 2 == 0 ? 100 : 200);
  const LayeredChannelFlow ref(s->wall_lo, s->wall_hi, s->interfaces, mus, 1.0, 1.0);
  for (int k = 0; k <= 50; ++k) {
    const double y = s->wall_lo + k / 50.0;
    EXPECT_DOUBLE_EQ(s->analytic_vx(y), ref.velocity(y));
  }
  EXPECT_DOUBLE_EQ(s->analytic_peak, ref.peak());
  EXPECT_NEAR(s->sound_speed, 10.0 * ref.peak(), 1e-15);
}

namespace {

struct LayeredRun {
  double max_rel = 0.0;  // max |v − V| / peak over the fluid particles
  double peak_rel = 0.0;  // (max v − max V) / max V, the paper's §7 metric
  double max_shift_dx = 0.0;  // largest y-displacement of a fluid particle, in ε'
  int strayed = 0;           // fluid particles whose phase no longer matches phase_at of their height
  SphRunResult run;
};

LayeredRun run_layered(const std::string& layout, const std::string& mean, double t_end) {
  const auto scene = layered(json{{"case", layout}, {"n_y", 32}, {"pair_viscosity_mean", mean}});
  ParticleSystem ps = scene->make_particles();
  const ParticleSystem initial = ps;
  SphRunOptions opt;
  opt.to_steady_state = false;
  opt.target_time = t_end;
  LayeredRun r;
  r.run = run_direct_sph(*scene, ps, opt);
  double vmax = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    r.max_rel = std::max(r.max_rel, std::abs(ps.vx[a] - scene->analytic_vx(ps.y[a])));
    vmax = std::max(vmax, ps.vx[a]);
    r.max_shift_dx = std::max(r.max_shift_dx, std::abs(ps.y[a] - initial.y[a]) / scene->dx);
    r.strayed += scene->phase(ps.y[a]) != ps.phase[a];
  }
  r.max_rel /= scene->analytic_peak;
  r.peak_rel = (vmax - scene->analytic_peak) / scene->analytic_peak;
  return r;
}

}  // namespace

// n_y = 32 (ε' = L/32), case 3 scaled: layers of 5 rows at rows 5 and 20. The slowest viscous mode decays like
// exp(−π² ν t / L²) with ν >= 100, so by t = 0.012 it is down by e^{−11.8} < 1e-5 of the peak.
TEST(LayeredDirectSph, SteadyProfileMatchesThePiecewiseParabolasAndInterfacesStay) {
  for (const std::string mean : {"arithmetic", "harmonic"}) {
    const LayeredRun r = run_layered("case3", mean, 0.012);
    std::cout << mean << ": max rel error " << r.max_rel << ", peak " << r.peak_rel << ", max y-shift "
              << r.max_shift_dx << " eps', steps " << r.run.steps << "\n";
    ASSERT_EQ(r.run.status, Status::target_time);
    // Interfaces stay put: at Re ~ 1e-5 the rows only slide along x, and the unlike-pair repulsion of (7.1)
    // moves them by ~1e-9 ε' in this time (measured); no particle leaves its phase's rows.
    EXPECT_EQ(r.strayed, 0);
    EXPECT_LT(r.max_shift_dx, 1e-7);  // measured 9.7e-10 (arithmetic) and 1.07e-9 (harmonic) eps'
    // The error is dominated by the zero-velocity wall (5.3), which shifts the effective walls by about one
    // spacing and overpredicts the flow by about 2ε'/W (DESIGN.md §6; W = L = 1): 6.25 % at n_y = 32. The layered
    // profile must be within that (measured: max 5.4 %, peak +3.3 % arithmetic / +5.1 % harmonic; both fall
    // like ε' — 3.6 % max at n_y = 48).
    const double wall_offset = 2.0 / 32;
    EXPECT_LT(r.max_rel, wall_offset);
    EXPECT_GT(r.peak_rel, 0.0);
    EXPECT_LT(r.peak_rel, wall_offset);
  }
}
