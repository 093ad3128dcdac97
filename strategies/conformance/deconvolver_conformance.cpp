// The deconvolver conformance checks; tests/conformance/test_deconvolver_conformance.cpp runs them for every
// built-in, a user's project for its own strategies (the header says how).
#include "strategies/conformance/deconvolver_conformance.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

namespace closurelab {
namespace {

using conformance::Expect;

struct Problem {
  ForwardOperator a;
  Eigen::VectorXd x, b;
};
// η = 1.5 h on 30 nodes: κ ≈ 1e2, SPD; x a smooth bump.
Problem make_problem(Discretization d = Discretization::coarse_coarse) {
  const UniformMesh1D c = UniformMesh1D::cell_centred(0, 1, 30, false), f = UniformMesh1D::cell_centred(0, 1, 60, false);
  const GaussianKernel k(1.5 * c.spacing);
  Problem p{make_averaging_operator_1d(k, c, f, d), {}, {}};
  const UniformMesh1D& s = p.a.solution_mesh->x;
  p.x.resize(s.count);
  for (int i = 0; i < s.count; ++i) p.x(i) = std::exp(-std::pow((s.node(i) - 0.45) / 0.15, 2));
  p.b = p.a.apply(p.x);
  return p;
}

bool supports_rule(const EntryInfo& info, const std::string& rule) {
  for (const auto& p : info.params)
    if (p.name == "rule") return std::find(p.choices.begin(), p.choices.end(), rule) != p.choices.end();
  return false;
}

struct Subject {
  const Family<Deconvolver>& family;
  std::string name;
  std::unique_ptr<Deconvolver> make(json extra = json::object()) const {
    extra["name"] = name;
    return family.create(extra, "/method");
  }
};

void schema_is_complete_and_defaults_resolve(const Subject& s, Expect& e) {
  const EntryInfo& info = s.family.info(s.name);
  e.that(!info.description.empty(), "the entry has a description");
  if (!e.that(supports_rule(info, "fixed"), "every method offers a fixed parameter (\"rule\" with choice \"fixed\")"))
    return;
  e.that(supports_rule(info, "discrepancy"), "every method offers the discrepancy principle (\"rule\" choice \"discrepancy\")");
  for (const auto& p : info.params) {
    e.that(!p.description.empty(), p.name + ": every parameter has a description");
    e.that(!p.default_value.is_null(), p.name + ": every parameter has a default");
  }
  const json r = s.family.resolve(json{{"name", s.name}}, "/method");
  for (const auto& p : info.params) e.that(r.contains(p.name), "resolved parameters echo " + p.name);
  e.throws_config_error([&] { s.make(json{{"no_such_parameter", 1}}); }, "an unknown parameter");
}

void fixed_solve_is_finite_consistent_and_repeatable(const Subject& s, Expect& e) {
  const Problem p = make_problem();
  auto d = s.make();
  e.that(d->name() == s.name, "name() is the registered name, got '" + d->name() + "'");
  d->setup(p.a);
  const DeconvolutionResult r = d->solve(p.b);
  if (!e.that(r.x.size() == p.a.cols(), "x has one entry per column of A")) return;
  e.that(r.x.allFinite(), "x is finite");
  e.that(r.status != DeconvolutionStatus::numerical_issue, "status is not numerical_issue: " + r.stats.message);
  // Reported norms are the true ones (to rounding).
  e.near(r.stats.residual_norm, (p.b - p.a.apply(r.x)).norm(), 1e-10 * p.b.norm(), "stats.residual_norm is ||b - A x||");
  e.near(r.stats.solution_norm, r.x.norm(), 1e-12 * r.x.norm(), "stats.solution_norm is ||x||");
  e.that(!r.stats.parameter_name.empty(), "stats.parameter_name is set");
  e.that(r.stats.rule == "fixed", "stats.rule is \"fixed\", got '" + r.stats.rule + "'");
  e.that(r.cost.matvecs >= 0, "cost.matvecs >= 0");
  e.that(r.cost.setup_seconds >= 0.0, "cost.setup_seconds >= 0");
  e.that(r.cost.solve_seconds >= 0.0, "cost.solve_seconds >= 0");
  // The default parameter on exact data beats the do-nothing answer (4.5 %) clearly: measured at most 0.63 %
  // (landweber order 1; the other built-ins 1e-14 to 6e-4).
  e.that((r.x - p.x).norm() < 0.01 * p.x.norm(), "the default parameters recover the bump to 1 %, relative error " +
                                                      std::to_string((r.x - p.x).norm() / p.x.norm()));
  // No hidden state: a second solve gives the same x.
  e.that((d->solve(p.b).x - r.x).norm() == 0.0, "a second solve gives the same x (no hidden state)");
  const json j = r.to_json();
  e.that(j.contains("status") && j.contains("stats") && j.contains("cost"), "to_json() has status, stats and cost");
}

void scan_reports_true_residuals_and_stops_when_asked(const Subject& s, Expect& e) {
  const Problem p = make_problem();
  auto d = s.make();
  d->setup(p.a);
  int visited = 0;
  bool saw_last = false;
  d->scan(p.b, [&](const ScanPoint& sp) {
    ++visited;
    const Eigen::VectorXd x = sp.solution();
    const std::string at = " at parameter " + std::to_string(sp.parameter);
    e.that(x.allFinite(), "scan: x is finite" + at);
    e.near(sp.residual_norm, (p.b - p.a.apply(x)).norm(), 1e-9 * p.b.norm(), "scan: residual_norm is ||b - A x||" + at);
    e.near(sp.solution_norm, x.norm(), 1e-9 * std::max(1.0, x.norm()), "scan: solution_norm is ||x||" + at);
    saw_last = sp.last;
    return visited < 25;
  });
  e.that(visited >= 1, "the scan visits at least one member");
  e.that(visited == 25 || saw_last, "the scan stopped when asked or marked its last member");
}

void discrepancy_principle_meets_tau_delta_or_says_so(const Subject& s, Expect& e) {
  const Problem p = make_problem();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0, 1);
  Eigen::VectorXd noise(p.b.size());
  for (auto& v : noise) v = n(rng);
  noise *= 1e-2 * p.b.norm() / noise.norm();
  auto d = s.make(json{{"rule", "discrepancy"}});
  d->setup(p.a);
  const DeconvolutionResult r = d->solve(p.b + noise, noise.norm());
  e.that(r.x.allFinite(), "x is finite");
  e.that(r.stats.rule == "discrepancy", "stats.rule is \"discrepancy\", got '" + r.stats.rule + "'");
  if (r.status == DeconvolutionStatus::converged)
    e.that(r.stats.residual_norm <= 1.01 * noise.norm() * (1 + 1e-12), "converged: ||b - A x|| <= tau delta");
  else
    e.that(!r.stats.message.empty(), "not converged: stats.message says why");
  // 1 % noise: the do-nothing answer's error is 4.7 %. Measured (seed 7): tsvd 0.74 %, cgls 0.80 %, relaxed
  // Landweber 1.0 %, landweber 1.9 %, cg 2.0 %, and tikhonov 4.2 % (biased: see kKnownWeak).
  e.that((r.x - p.x).norm() < 0.05 * p.x.norm(), "1 % noise: the bump is recovered to 5 %, relative error " +
                                                      std::to_string((r.x - p.x).norm() / p.x.norm()));
}

// "Clearly better than doing nothing": at most half the do-nothing error.
constexpr double kBeatFactor = 0.5;

// Built-in combinations measured NOT to beat the do-nothing answer clearly on this problem: real weaknesses of
// the rules, not tolerances: the L-curve corner is found on the under-regularized branch at 1 % noise (tikhonov:
// 43 % error), GCV of Tikhonov under-regularizes, and the discrepancy principle's Tikhonov answer is biased
// (3.2 % at 1 % noise). Each is held to its measured ratio (+25 %) so that it cannot get worse unnoticed;
// removing an entry once a rule is fixed makes the check bite. Any other strategy is held to kBeatFactor.
struct KnownWeak {
  const char* method;
  const char* rule;
  double noise, measured_ratio;
};
constexpr KnownWeak kKnownWeak[] = {
    {"tikhonov", "discrepancy", 1e-2, 0.674}, {"tikhonov", "gcv", 1e-3, 0.66}, {"tikhonov", "gcv", 1e-2, 1.12},
    {"tikhonov", "lcurve", 1e-3, 0.95},       {"tikhonov", "lcurve", 1e-2, 9.03}, {"cgls", "lcurve", 1e-3, 0.869},
    {"cgls", "lcurve", 1e-2, 0.571},          {"landweber", "lcurve", 1e-3, 0.883}, {"landweber", "lcurve", 1e-2, 1.43},
    {"landweber_relaxed", "lcurve", 1e-2, 1.37}, {"cg", "lcurve", 1e-2, 1.19},    {"tsvd", "lcurve", 1e-2, 2.23}};

double allowed_ratio(const std::string& method, const std::string& rule, double noise) {
  for (const auto& k : kKnownWeak)
    if (method == k.method && rule == k.rule && noise == k.noise) return 1.25 * k.measured_ratio;
  return kBeatFactor;
}

// The do-nothing answer x = b (the data taken as the solution: the zero-order closure) has a 4.5 % error on
// this problem. Every rule a method offers must beat it clearly, however its status reads: the fixed default
// on exact data, and every parameter-choice rule on data with 0.1 % and 1 % noise (δ given).
void every_rule_beats_the_do_nothing_answer_clearly(const Subject& s, Expect& e) {
  const Problem p = make_problem();
  const EntryInfo& info = s.family.info(s.name);
  int rules = 0;
  for (const char* rule : {"fixed", "discrepancy", "gcv", "lcurve"}) {
    if (!supports_rule(info, rule)) continue;
    ++rules;
    const bool fixed = std::string(rule) == "fixed";
    for (double noise : fixed ? std::vector<double>{0.0} : std::vector<double>{1e-3, 1e-2}) {
      const std::string at = std::string(" (rule ") + rule + ", noise " + std::to_string(noise) + ")";
      std::mt19937_64 rng(11);
      std::normal_distribution<double> n(0, 1);
      Eigen::VectorXd err(p.b.size());
      for (auto& v : err) v = n(rng);
      err *= noise * p.b.norm() / err.norm();
      const double do_nothing = (p.b + err - p.x).norm() / p.x.norm();
      auto d = s.make(json{{"rule", rule}});
      try {
        d->setup(p.a);
      } catch (const ConfigError& c) {  // a rule this configuration cannot use must say why, naming the key
        e.that(std::string(c.what()).find('/') != std::string::npos, std::string("a refusal names its key: ") + c.what() + at);
        continue;
      }
      const DeconvolutionResult r = d->solve(p.b + err, err.norm());
      if (!e.that(r.x.size() == p.a.cols(), "x has one entry per column of A" + at)) continue;
      e.that(r.status != DeconvolutionStatus::numerical_issue, "status is not numerical_issue: " + r.stats.message + at);
      const double error = (r.x - p.x).norm() / p.x.norm();
      const double allowed = allowed_ratio(s.name, rule, noise);
      e.that(error < allowed * do_nothing, "error " + std::to_string(error) + " is not below " + std::to_string(allowed) +
                                               " x the do-nothing error " + std::to_string(do_nothing) + at);
    }
  }
  e.that(rules >= 2, "every method offers fixed and at least one rule");
}

void rectangular_operator_is_handled_or_refused_clearly(const Subject& s, Expect& e) {
  const Problem p = make_problem(Discretization::coarse_fine);
  auto d = s.make();
  try {
    d->setup(p.a);
  } catch (const ConfigError& err) {
    e.that(std::string(err.what()).find("square") != std::string::npos,
           std::string("a refusal names the need for a square operator: ") + err.what());
    return;
  }
  const DeconvolutionResult r = d->solve(p.b);
  e.that(r.x.size() == p.a.cols(), "x has one entry per column of A");
  e.that(r.x.allFinite(), "x is finite");
  if (r.status == DeconvolutionStatus::numerical_issue) e.that(!r.stats.message.empty(), "numerical_issue: stats.message says why");
}

void bad_data_is_a_config_error(const Subject& s, Expect& e) {
  const Problem p = make_problem();
  auto d = s.make();
  d->setup(p.a);
  Eigen::VectorXd b = p.b;
  b(0) = INFINITY;
  e.throws_config_error([&] { d->solve(b); }, "a non-finite b");
  e.throws_config_error([&] { d->solve(p.b.head(5)); }, "a b of the wrong size");
}

using Check = void (*)(const Subject&, Expect&);
const std::vector<std::pair<std::string, Check>>& all_checks() {
  static const std::vector<std::pair<std::string, Check>> checks = {
      {"schema_is_complete_and_defaults_resolve", schema_is_complete_and_defaults_resolve},
      {"fixed_solve_is_finite_consistent_and_repeatable", fixed_solve_is_finite_consistent_and_repeatable},
      {"scan_reports_true_residuals_and_stops_when_asked", scan_reports_true_residuals_and_stops_when_asked},
      {"discrepancy_principle_meets_tau_delta_or_says_so", discrepancy_principle_meets_tau_delta_or_says_so},
      {"rectangular_operator_is_handled_or_refused_clearly", rectangular_operator_is_handled_or_refused_clearly},
      {"bad_data_is_a_config_error", bad_data_is_a_config_error},
      {"every_rule_beats_the_do_nothing_answer_clearly", every_rule_beats_the_do_nothing_answer_clearly}};
  return checks;
}

}  // namespace

const std::vector<std::string>& deconvolver_conformance_checks() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& [name, f] : all_checks()) v.push_back(name);
    return v;
  }();
  return names;
}

ConformanceReport run_deconvolver_conformance(const Registry& registry, const std::string& name, const std::string& check) {
  registry.deconvolvers.info(name, "/deconvolver/name");  // ConfigError listing the known names
  return conformance::run_checks(name, Subject{registry.deconvolvers, name}, all_checks(), check);
}

}  // namespace closurelab
