// The stress-quadrature conformance checks; tests/conformance/test_strategy_conformance.cpp runs them for every
// registered quadrature. Every comparison is relative to the largest stress component of the reference, at
// 1e-12: the quadratures and the reference sum the same pair forces with the same bond integrals, in another
// order (the built-ins agree to 2e-14 of the largest component or better, measured).
#include "strategies/conformance/quadrature_conformance.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>

#include "core/averaging/averaging.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

namespace closurelab {
namespace {

using conformance::Expect;
using Stress = std::map<std::string, Eigen::VectorXd>;
using Field = std::function<Vec2(const Vec2&)>;

const std::vector<std::string> kAll{"xx", "xy", "yx", "yy"};

struct Subject {
  const Registry& registry;
  std::string name;
  json finest;
  std::unique_ptr<StressQuadrature> make(bool at_finest) const {
    json c = at_finest ? finest : json::object();
    c["name"] = name;
    return registry.quadratures.create(c, "/quadrature");
  }
  std::unique_ptr<Scene> channel(const std::string& walls) const {
    return registry.scenes.create(json{{"name", "poiseuille-uniform"}, {"n_y", 32}, {"n_x", 12}, {"eta_over_ly", 1.0 / 16},
                                       {"wall_model", walls}},
                                  "/scene");
  }
};

// A fully periodic, wall-free 16 x 16 lattice on [0, 0.5)² (not x-invariant).
Scene periodic_box() {
  Scene s;
  s.name = "periodic-box";
  s.nx = s.ny = 16;
  s.dx = 0.5 / 16;
  s.eta = 0.08;
  s.box = PeriodicBox{0.5, 0.5, true, true};
  s.has_walls = false;
  s.x_invariant = false;
  s.force_x = [](double) { return 0.0; };
  s.h = s.dx;
  s.sound_speed = 1.0;
  s.background_pressure = 0.5;
  s.phase_viscosity = {1.5};
  return s;
}

VelocitySampler sampler_of(const Scene& s, Field v) {
  return [&s, v](const std::vector<Vec2>& pts) {
    Eigen::Matrix2Xd out(2, pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) out.col(k) = s.is_wall(pts[k].y()) ? Vec2::Zero() : v(pts[k]);
    return out;
  };
}

// The reference: the averaging operator's (2.13) for the particles carrying `v` (walls at rest).
Stress pair_sum(const Scene& s, const AveragingKernel& k, const TensorMesh2D& mesh, const Field& v) {
  ParticleSystem ps = s.make_particles();
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) {
      const Vec2 u = v(Vec2(ps.x[a], ps.y[a]));
      ps.vx[a] = u.x();
      ps.vy[a] = u.y();
    }
  SphEngine engine(s, ps);
  AveragingRequest req;
  req.interaction = true;
  req.components = kAll;
  return average_particles(ps, s.box, k, mesh, req, engine.pair_forces()).interaction;
}

double largest(const Stress& t) {
  double m = 0.0;
  for (const auto& [c, f] : t) m = std::max(m, f.cwiseAbs().maxCoeff());
  return m;
}

// Every component of `got` within 1e-12 of `scale` (default: the largest component of `ref`).
void expect_same(Expect& e, const Stress& got, const Stress& ref, const std::string& what, double scale = 0.0) {
  if (scale == 0.0) scale = largest(ref);
  e.that(scale > 0.0 && std::isfinite(scale), what + ": the reference stress is zero or not finite");
  for (const auto& [c, f] : ref) {
    if (!e.that(got.count(c) && got.at(c).size() == f.size(), what + ": component " + c + " missing or of the wrong size"))
      continue;
    const double diff = (got.at(c) - f).cwiseAbs().maxCoeff();
    e.near(diff, 0.0, 1e-12 * scale, what + ", component " + c + ": max difference");
  }
}

Stress combine(double a, const Stress& u, double b, const Stress& w, double c, const Stress& z) {
  Stress out;
  for (const auto& [k, f] : u) out[k] = a * f + b * w.at(k) + c * z.at(k);
  return out;
}

void finest_setting_is_the_exact_pair_sum(const Subject& s, Expect& e) {
  for (const std::string walls : {"zero_velocity", "ghost_velocity"}) {
    const auto sc = s.channel(walls);
    const GaussianKernel k(sc->eta);
    const TensorMesh2D mesh{UniformMesh1D::cell_centred(0.0, sc->box.lx, 2, true),
                            UniformMesh1D::cell_centred(0.0, sc->box.ly, 24, false)};
    const double kx = 2.0 * M_PI / sc->box.lx;
    const Field v = [&](const Vec2& p) {
      return Vec2(sc->analytic_vx(p.y()) * (1.0 + 0.1 * std::sin(kx * p.x())), 0.01 * std::cos(kx * p.x() + 3.0 * p.y()));
    };
    const auto q = s.make(true);
    q->setup(*sc, k, mesh, kAll);
    expect_same(e, q->evaluate(sampler_of(*sc, v)).stress, pair_sum(*sc, k, mesh, v), "channel, " + walls + " walls");
  }
}

void virial_identity_on_a_periodic_box(const Subject& s, Expect& e) {
  const Scene sc = periodic_box();
  const Field v = [](const Vec2& p) {
    return Vec2(std::sin(4.0 * M_PI * p.y()) + 0.3 * std::cos(4.0 * M_PI * p.x()), 0.2 * std::sin(4.0 * M_PI * p.x()));
  };
  const auto axis = UniformMesh1D::cell_centred(0.0, 0.5, 12, true);
  const TensorMesh2D mesh{axis, axis};
  const auto q = s.make(true);
  q->setup(sc, GaussianKernel(sc.eta), mesh, kAll);
  const Stress t = q->evaluate(sampler_of(sc, v)).stress;
  ParticleSystem ps = sc.make_particles();
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const Vec2 u = v(Vec2(ps.x[a], ps.y[a]));
    ps.vx[a] = u.x();
    ps.vy[a] = u.y();
  }
  SphEngine engine(sc, ps);
  Eigen::Matrix2d virial = Eigen::Matrix2d::Zero();
  for (const auto& p : engine.pair_forces()) virial += p.f * p.d.transpose();
  // The trapezoid rule on the periodic mesh is spectrally accurate for the smooth periodic integrand
  // (error ~ exp(−π² η²/Δ²) ≈ 2e-16 at η = 0.08, Δ = 0.5/12): the identity holds to round-off.
  const double scale = virial.cwiseAbs().maxCoeff();
  for (const auto& c : kAll) {
    const auto [a, b] = component_index(c);
    if (!e.that(t.count(c) > 0, "component " + c + " missing")) continue;
    e.near(t.at(c).sum() * mesh.cell_area(), virial(a, b), 1e-12 * scale, "integral of T_" + c + " vs the pair virial");
  }
}

void affine_in_velocity_and_blind_to_translation(const Subject& s, Expect& e) {
  for (const bool at_finest : {false, true}) {
    const std::string setting = at_finest ? "finest setting" : "default setting";
    // x-invariant fields on the channel: every setting must accept them (the coarse default integrates x).
    const auto sc = s.channel("zero_velocity");
    const GaussianKernel k(sc->eta);
    const TensorMesh2D mesh = column_mesh(sc->box, 0.5 * sc->eta);
    const auto q = s.make(at_finest);
    q->setup(*sc, k, mesh, kAll);
    const Field u = [&](const Vec2& p) { return Vec2(sc->analytic_vx(p.y()), 0.02 * std::sin(2.0 * M_PI * p.y())); };
    const Field w = [](const Vec2& p) { return Vec2(std::cos(3.0 * M_PI * p.y()), 0.1 * p.y()); };
    const double a = 0.7, b = -1.3;
    const Stress t0 = q->evaluate(sampler_of(*sc, [](const Vec2&) { return Vec2(0.0, 0.0); })).stress;
    const Stress tu = q->evaluate(sampler_of(*sc, u)).stress, tw = q->evaluate(sampler_of(*sc, w)).stress;
    const Stress tab = q->evaluate(sampler_of(*sc, [&](const Vec2& p) { return Vec2(a * u(p) + b * w(p)); })).stress;
    expect_same(e, combine(1.0, tab, -1.0, t0, 0.0, t0), combine(a, tu, b, tw, -(a + b), t0),
                setting + ": T(a u + b w) - T(0) vs a (T(u) - T(0)) + b (T(w) - T(0))",
                std::max({largest(t0), largest(tu), largest(tw), largest(tab)}));  // round-off of the terms
  }
  const Scene box = periodic_box();
  const auto axis = UniformMesh1D::cell_centred(0.0, 0.5, 12, true);
  const TensorMesh2D mesh{axis, axis};
  const auto q = s.make(true);
  q->setup(box, GaussianKernel(box.eta), mesh, kAll);
  const Field v = [](const Vec2& p) { return Vec2(std::sin(4.0 * M_PI * p.y()), 0.5 * std::cos(4.0 * M_PI * p.x())); };
  const Stress tv = q->evaluate(sampler_of(box, v)).stress;
  const Stress moved = q->evaluate(sampler_of(box, [&](const Vec2& p) { return Vec2(v(p) + Vec2(0.8, -0.4)); })).stress;
  expect_same(e, moved, tv, "periodic box, finest setting: T(v + c) vs T(v)");
}

void reports_each_call(const Subject& s, Expect& e) {
  const auto sc = s.channel("zero_velocity");
  const auto q = s.make(false);
  q->setup(*sc, GaussianKernel(sc->eta), column_mesh(sc->box, 0.5 * sc->eta), {"xy"});
  const auto v = sampler_of(*sc, [&](const Vec2& p) { return Vec2(sc->analytic_vx(p.y()), 0.0); });
  const QuadratureResult r = q->evaluate(v);
  e.that(r.status == Status::converged, "a smooth field gives status converged: " + r.message);
  e.that(r.pair_forces > 0 && r.seconds >= 0.0, "the call reports its pair forces and seconds");
  const QuadratureCost c = q->setup_cost();
  e.that(c.bond_weights >= 0 && c.sample_points >= 0 && c.setup_seconds >= 0.0, "a setup cost counter is negative");
  // A non-finite velocity field is a numerical issue with a reason, not an exception or a silent NaN.
  const QuadratureResult bad = q->evaluate([](const std::vector<Vec2>& points) {
    return Eigen::Matrix2Xd::Constant(2, static_cast<Eigen::Index>(points.size()), std::nan(""));
  });
  e.that(bad.status == Status::numerical_issue && !bad.message.empty(),
         "a non-finite velocity gives numerical_issue with a message");
}

using Check = void (*)(const Subject&, Expect&);
const std::vector<std::pair<std::string, Check>>& all_checks() {
  static const std::vector<std::pair<std::string, Check>> checks = {
      {"finest_setting_is_the_exact_pair_sum", finest_setting_is_the_exact_pair_sum},
      {"virial_identity_on_a_periodic_box", virial_identity_on_a_periodic_box},
      {"affine_in_velocity_and_blind_to_translation", affine_in_velocity_and_blind_to_translation},
      {"reports_each_call", reports_each_call}};
  return checks;
}

}  // namespace

const std::vector<std::string>& quadrature_conformance_checks() {
  static const std::vector<std::string> names = conformance::check_names(all_checks());
  return names;
}

ConformanceReport run_quadrature_conformance(const Registry& registry, const std::string& name, const json& finest,
                                             const std::string& check) {
  registry.quadratures.info(name, "/quadrature/name");  // ConfigError listing the known names
  if (!finest.is_object()) throw ConfigError("", "the finest setting of a quadrature is a JSON object of its parameters");
  return conformance::run_checks(name, Subject{registry, name, finest}, all_checks(), check);
}

}  // namespace closurelab
