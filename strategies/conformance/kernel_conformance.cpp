// The averaging-kernel conformance checks; tests/conformance/test_strategy_conformance.cpp runs them for every
// registered kernel. Each tolerance is argued where it is used; the built-ins meet each by a factor of 10 or more.
#include "strategies/conformance/kernel_conformance.hpp"

#include <gsl/gsl_deriv.h>
#include <gsl/gsl_integration.h>

#include <cmath>
#include <functional>
#include <memory>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/gsl_support.hpp"

namespace closurelab {
namespace {

using conformance::Expect;

struct Subject {
  const Family<AveragingKernel>& family;
  std::string name;
  std::unique_ptr<AveragingKernel> make(double eta) const { return family.create(json{{"name", name}, {"eta", eta}}, "/kernel"); }
};

// The window lengths every check runs at.
const double kEtas[] = {0.0625, 0.3};

// ∫_a^b f by GSL QAGS (adaptive, with extrapolation: it copes with a cut-off window's jumps), relative target
// 1e-13; `error` receives GSL's estimate of the absolute error.
double integrate(const std::function<double(double)>& f, double a, double b, double* error = nullptr) {
  gsl_errors_as_status();
  gsl_function F;
  F.function = [](double x, void* p) { return (*static_cast<const std::function<double(double)>*>(p))(x); };
  F.params = const_cast<std::function<double(double)>*>(&f);
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(5000);
  double r = 0.0, err = 0.0;
  gsl_integration_qags(&F, a, b, 0.0, 1e-13, 5000, w, &r, &err);
  gsl_integration_workspace_free(w);
  if (error) *error = err;
  return r;
}

std::string at_eta(double eta) { return " (eta " + std::to_string(eta) + ")"; }

void window_is_even_nonnegative_and_supported(const Subject& s, Expect& e) {
  for (double eta : kEtas) {
    const auto k = s.make(eta);
    e.that(k->name() == s.name, "name() is '" + k->name() + "', registered as '" + s.name + "'");
    e.near(k->eta(), eta, 0.0, "eta()" + at_eta(eta));
    const double r = k->support_radius(), peak = k->factor(0.0);
    if (!e.that(std::isfinite(r) && r > 0.0, "support_radius() is not a positive number" + at_eta(eta))) continue;
    e.that(std::isfinite(peak) && peak > 0.0, "factor(0) is not a positive number" + at_eta(eta));
    for (double t = -1.2 * r; t <= 1.2 * r; t += 0.01 * r) {
      const double f = k->factor(t);
      e.that(std::isfinite(f) && f >= 0.0, "factor(" + std::to_string(t) + ") is negative or not finite" + at_eta(eta));
      e.near(f, k->factor(-t), 1e-15 * peak, "factor is not even at t = " + std::to_string(t) + at_eta(eta));
    }
    // Beyond the support the window is negligible (the Gaussian's 6η: exp(−36) ≈ 2.3e-16 of its peak).
    for (double m : {1.0001, 1.5, 3.0, 10.0})
      e.that(k->factor(m * r) <= 1e-15 * peak, "factor(" + std::to_string(m) + " support_radius) is above 1e-15 of its peak" + at_eta(eta));
  }
}

// ∫ φ = 1 over the support; QAGS reaches 1e-13 and the tail beyond the support is below 1e-15 η φ(0): 1e-12.
void normalization_is_one(const Subject& s, Expect& e) {
  for (double eta : kEtas) {
    const auto k = s.make(eta);
    const double r = k->support_radius();
    e.near(integrate([&](double t) { return k->factor(t); }, -r, r), 1.0, 1e-12, "integral of the factor" + at_eta(eta));
  }
}

// The symbol against ∫ φ(t) cos(2πξt) dt (φ even, so its transform is real) from ξη = 0 to 2.5, where the
// Gaussian's symbol has fallen to exp(−π² 6.25) ≈ 2e-27: absolute 1e-12 (the symbol is at most 1).
void fourier_symbol_matches_quadrature(const Subject& s, Expect& e) {
  for (double eta : kEtas) {
    const auto k = s.make(eta);
    const double r = k->support_radius();
    e.near(k->factor_symbol(0.0), 1.0, 1e-12, "factor_symbol(0)" + at_eta(eta));
    for (double xi_eta : {0.1, 0.3, 0.7, 1.0, 1.6, 2.5}) {
      const double xi = xi_eta / eta;
      const double q = integrate([&](double t) { return k->factor(t) * std::cos(2.0 * M_PI * xi * t); }, -r, r);
      e.near(k->factor_symbol(xi), q, 1e-12, "factor_symbol(" + std::to_string(xi_eta) + "/eta) vs quadrature" + at_eta(eta));
    }
  }
}

// (A.1) against QAGS along the bond, relative 1e-12 (QAGS's target is 1e-13; the built-ins agree to 4e-15),
// with an absolute floor of 1e-14 ψ(0) for bonds outside a cut-off window.
void bond_integral_matches_quadrature_and_short_bond_limit(const Subject& s, Expect& e) {
  struct Bond {
    const char* what;
    Vec2 x, qj, qk;  // in units of η
  };
  const Bond bonds[] = {{"centre on the bond", {0.1, 0.0}, {0.0, 0.0}, {0.3, 0.0}},
                        {"near, oblique", {0.5, 0.7}, {0.2, -0.1}, {0.4, 0.25}},
                        {"long bond across the centre", {0.0, 0.2}, {-2.0, -1.0}, {2.5, 1.5}},
                        {"far along the bond", {4.5, 0.0}, {0.0, 0.0}, {0.05, 0.0}},
                        {"far, oblique", {-2.4, 1.8}, {0.0, 0.0}, {0.04, 0.03}},
                        {"beyond one end", {2.9, 0.4}, {0.0, 0.0}, {1.0, 0.0}},
                        {"SPH-size bond", {1.9, 1.0}, {0.0, 0.0}, {0.25, 0.125}}};
  for (double eta : kEtas) {
    const auto k = s.make(eta);
    const double psi0 = k->value(Vec2::Zero());
    for (const auto& b : bonds) {
      const Vec2 x = eta * b.x, qj = eta * b.qj, qk = eta * b.qk;
      const double ref = integrate([&](double t) { return k->value(t * (x - qk) + (1 - t) * (x - qj)); }, 0.0, 1.0);
      const double got = k->bond_integral(x, qj, qk), tol = 1e-12 * std::abs(ref) + 1e-14 * psi0;
      e.near(got, ref, tol, std::string("bond integral, ") + b.what + at_eta(eta));
      e.near(k->bond_integral(x, qk, qj), got, tol, std::string("bond integral with its ends swapped, ") + b.what + at_eta(eta));
    }
    // |q_k − q_j| → 0: ∫₀¹ ψ(x − q − s d) ds = ψ(x − q) − ∇ψ·d/2 + O(|d|²); for the Gaussian family the relative
    // first-order term is (x − q)·d/η², at most |x − q||d|/η² = 0.53 len for d = (1, 0.5) len η here (the
    // built-ins: 0.05 len): relative len; the zero-length bond is ψ(x − q) itself (relative 1e-14; measured 7e-16).
    const Vec2 x = eta * Vec2(0.3, -0.2), q = eta * Vec2(0.05, 0.2);
    const double psi = k->value(x - q);
    for (double len : {1e-3, 1e-6, 1e-9})
      e.near(k->bond_integral(x, q, q + eta * Vec2(len, 0.5 * len)) / psi, 1.0, len + 1e-13,
             "short-bond limit, |d|/eta = " + std::to_string(len) + at_eta(eta));
    e.near(k->bond_integral(x, q, q) / psi, 1.0, 1e-14, "zero-length bond" + at_eta(eta));
  }
}

// φ' against GSL's central difference of φ (gsl_deriv_central, step η/100, 5-point rule: truncation ~1e-10 of
// φ(0)/η for the Gaussian) over the support, away from a cut-off window's jumps at ±support_radius: absolute
// 1e-8 φ(0)/η plus ten times GSL's error estimate.
void factor_derivative_matches_difference_quotient(const Subject& s, Expect& e) {
  for (double eta : kEtas) {
    const auto k = s.make(eta);
    const double r = k->support_radius(), scale = k->factor(0.0) / eta, h = 0.01 * eta;
    gsl_errors_as_status();
    gsl_function F;
    F.function = [](double t, void* p) { return static_cast<const AveragingKernel*>(p)->factor(t); };
    F.params = const_cast<AveragingKernel*>(k.get());
    for (double t = -0.97 * r; t <= 0.97 * r; t += 0.0485 * r) {
      if (r - std::abs(t) < 4.0 * h) continue;
      double d = 0.0, err = 0.0;
      gsl_deriv_central(&F, t, h, &d, &err);
      e.near(k->factor_derivative(t), d, 1e-8 * scale + 10.0 * err,
             "factor_derivative(" + std::to_string(t / eta) + " eta) vs the central difference" + at_eta(eta));
    }
  }
}

using Check = void (*)(const Subject&, Expect&);
const std::vector<std::pair<std::string, Check>>& all_checks() {
  static const std::vector<std::pair<std::string, Check>> checks = {
      {"window_is_even_nonnegative_and_supported", window_is_even_nonnegative_and_supported},
      {"normalization_is_one", normalization_is_one},
      {"fourier_symbol_matches_quadrature", fourier_symbol_matches_quadrature},
      {"bond_integral_matches_quadrature_and_short_bond_limit", bond_integral_matches_quadrature_and_short_bond_limit},
      {"factor_derivative_matches_difference_quotient", factor_derivative_matches_difference_quotient}};
  return checks;
}

}  // namespace

const std::vector<std::string>& kernel_conformance_checks() {
  static const std::vector<std::string> names = conformance::check_names(all_checks());
  return names;
}

ConformanceReport run_kernel_conformance(const Registry& registry, const std::string& name, const std::string& check) {
  registry.kernels.info(name, "/kernel/name");  // ConfigError listing the known names
  return conformance::run_checks(name, Subject{registry.kernels, name}, all_checks(), check);
}

}  // namespace closurelab
