// The scene conformance checks; tests/conformance/test_strategy_conformance.cpp runs them for every registered
// scene (and a few parameter sets of each). Round-off allowance: a velocity evaluated to a few ulps of the peak
// (64 ε |v|_max per value), divided by the difference step's power.
#include "strategies/conformance/scene_conformance.hpp"

#include <cmath>
#include <limits>
#include <memory>

#include "core/sph/scene.hpp"

namespace closurelab {
namespace {

using conformance::Expect;

constexpr double kUlps = 64 * std::numeric_limits<double>::epsilon();

struct Subject {
  const Registry& registry;
  std::string name;
  json params;
  std::unique_ptr<Scene> make() const {
    json c = params;
    c["name"] = name;
    return registry.scenes.create(c, "/scene");
  }
};

// The channel (between the wall surfaces) or, without walls, the periodic height.
std::pair<double, double> extent(const Scene& s) {
  return s.has_walls ? std::pair{s.wall_lo, s.wall_hi} : std::pair{0.0, s.box.ly};
}

double mu_at(const Scene& s, double y) { return s.phase_viscosity.at(s.phase(y)); }

double dense_peak(const Scene& s) {
  const auto [lo, hi] = extent(s);
  double m = 0.0;
  for (int k = 0; k <= 100000; ++k) m = std::max(m, std::abs(s.analytic_vx(lo + (hi - lo) * k / 100000.0)));
  return m;
}

std::string at(double y) { return " at y = " + std::to_string(y); }

void analytic_solution_satisfies_its_ode(const Subject& subject, Expect& e) {
  const auto s = subject.make();
  if (!s->analytic_vx) return;
  const auto [lo, hi] = extent(*s);
  const double w = hi - lo, d = w / 400, vmax = dense_peak(*s);
  const auto& v = s->analytic_vx;
  const auto d2 = [&](double y, double h) { return (v(y + h) - 2 * v(y) + v(y - h)) / (h * h); };
  int checked = 0;
  for (int k = 0; k <= 200; ++k) {
    const double y = lo + 2 * d + (w - 4 * d) * k / 200.0;
    bool near_interface = false;
    for (double yi : s->interfaces) near_interface |= std::abs(y - yi) <= 1.5 * d;
    if (near_interface) continue;
    const double mu = mu_at(*s, y), coarse = d2(y, d), fine = d2(y, d / 2);
    // fine's truncation error is about (coarse − fine)/3 (O(h²)); allow twice that, plus round-off.
    const double tol = mu * (2.0 * std::abs(coarse - fine) / 3.0 + kUlps * vmax / (d * d / 4));
    e.near(mu * fine, -s->rho0 * s->force_x(y), tol, "mu v'' vs -rho f_x" + at(y));
    ++checked;
  }
  e.that(checked >= 50, "fewer than 50 heights away from the interfaces: " + std::to_string(checked));
}

void interfaces_carry_continuous_velocity_and_shear_stress(const Subject& subject, Expect& e) {
  const auto s = subject.make();
  if (!s->analytic_vx) return;
  const auto [lo, hi] = extent(*s);
  const double vmax = dense_peak(*s);
  const auto& v = s->analytic_vx;
  for (std::size_t i = 0; i < s->interfaces.size(); ++i) {
    const double yi = s->interfaces[i];
    double gap = std::min(yi - lo, hi - yi);  // the step stays inside the two segments at the interface
    if (i > 0) gap = std::min(gap, yi - s->interfaces[i - 1]);
    if (i + 1 < s->interfaces.size()) gap = std::min(gap, s->interfaces[i + 1] - yi);
    const double d = gap / 4, tiny = 1e-12 * (hi - lo);
    // One-sided second-order differences from each side, at steps d and d/2.
    const auto below = [&](double h) { return (3 * v(yi) - 4 * v(yi - h) + v(yi - 2 * h)) / (2 * h); };
    const auto above = [&](double h) { return -(3 * v(yi) - 4 * v(yi + h) + v(yi + 2 * h)) / (2 * h); };
    e.near(v(yi - tiny), v(yi + tiny), kUlps * vmax + 2 * tiny * (std::abs(below(d)) + std::abs(above(d))),
           "v across the interface" + at(yi));
    const double mu_lo = mu_at(*s, yi - d / 4), mu_hi = mu_at(*s, yi + d / 4);
    const double tol = 2.0 * (mu_lo * std::abs(below(d) - below(d / 2)) + mu_hi * std::abs(above(d) - above(d / 2))) / 3.0 +
                       (mu_lo + mu_hi) * 8 * kUlps * vmax / d;
    e.near(mu_lo * below(d / 2), mu_hi * above(d / 2), tol, "shear stress mu v' across the interface" + at(yi));
  }
}

void wall_conditions_hold(const Subject& subject, Expect& e) {
  const auto s = subject.make();
  if (!s->analytic_vx) return;
  const double vmax = dense_peak(*s), ly = s->box.ly;
  const auto& v = s->analytic_vx;
  if (s->has_walls) {
    e.near(v(s->wall_lo), 0.0, kUlps * vmax, "v on the lower wall surface");
    e.near(v(s->wall_hi), 0.0, kUlps * vmax, "v on the upper wall surface");
    for (int k = 0; k <= 20; ++k) {
      const double below = s->wall_lo * k / 20.0 * 0.999, above = ly - (ly - s->wall_hi) * k / 20.0 * 0.999;
      e.near(v(below), 0.0, 0.0, "v inside the lower wall" + at(below));
      e.near(v(above), 0.0, 0.0, "v inside the upper wall" + at(above));
    }
  } else {
    const double d = ly / 400;
    e.near(v(0.0), v(ly), kUlps * vmax, "v(0) vs v(L_y), periodic");
    e.near((v(d) - v(-d)) / (2 * d), (v(ly + d) - v(ly - d)) / (2 * d), 2 * kUlps * vmax / d, "v'(0) vs v'(L_y), periodic");
  }
}

void analytic_peak_is_the_maximum(const Subject& subject, Expect& e) {
  const auto s = subject.make();
  if (!s->analytic_vx) return;
  const double dense = dense_peak(*s);
  e.that(dense > 0.0 && std::isfinite(dense), "the analytic solution is zero or not finite");
  e.near(s->analytic_peak, dense, 1e-5 * dense, "analytic_peak vs max |v| over 100001 heights");
  // The samples miss the true maximum by at most (Δ/2)² |v''| / 2 ≈ 1e-10 |v|_max for a parabola (Δ = W/1e5):
  // a peak above the samples by more than 1e-8 is not the solution's.
  e.that(s->analytic_peak <= dense * (1 + 1e-8), "analytic_peak exceeds max |v| by more than 1e-8");
  if (const auto& m = s->steady_sine_mode) {
    const auto [lo, hi] = extent(*s);
    for (int k = 0; k <= 100; ++k) {
      const double y = lo + (hi - lo) * k / 100.0;
      e.near(s->analytic_vx(y), m->amplitude * std::sin(m->wavenumber * y), kUlps * dense, "declared sine mode" + at(y));
    }
  }
}

using Check = void (*)(const Subject&, Expect&);
const std::vector<std::pair<std::string, Check>>& all_checks() {
  static const std::vector<std::pair<std::string, Check>> checks = {
      {"analytic_solution_satisfies_its_ode", analytic_solution_satisfies_its_ode},
      {"interfaces_carry_continuous_velocity_and_shear_stress", interfaces_carry_continuous_velocity_and_shear_stress},
      {"wall_conditions_hold", wall_conditions_hold},
      {"analytic_peak_is_the_maximum", analytic_peak_is_the_maximum}};
  return checks;
}

}  // namespace

const std::vector<std::string>& scene_conformance_checks() {
  static const std::vector<std::string> names = conformance::check_names(all_checks());
  return names;
}

ConformanceReport run_scene_conformance(const Registry& registry, const std::string& name, const json& params,
                                        const std::string& check) {
  registry.scenes.info(name, "/scene/name");
  if (!params.is_object()) throw ConfigError("", "scene parameters must be a JSON object");
  const Subject subject{registry, name, params};
  subject.make();  // parameters the scene refuses: a ConfigError here, not a failure of every check
  return conformance::run_checks(name, subject, all_checks(), check);
}

}  // namespace closurelab
