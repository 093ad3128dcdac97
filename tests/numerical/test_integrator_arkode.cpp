// The SUNDIALS ARKODE integrators (core/reduced/integrator_arkode.cpp): arkode_erk with forward Euler at the fixed
// step reproduces the explicit step; the adaptive ones meet the exact solution of linear problems within a bound
// set by their tolerances, and tighter tolerances give smaller errors; arkode_imex steps a stiff split system with
// few explicit evaluations, by GMRES or by the LU of its probed Jacobian (linear_solver dense); the 1D quick spec run through the spec path; bad parameters refused at their path.
#include <gtest/gtest.h>

#include <unsupported/Eigen/MatrixFunctions>
#include <cmath>
#include <fstream>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/reduced/integrator.hpp"
#include "experiments/kinds/experiment_kind.hpp"

using namespace closurelab;

namespace {

std::unique_ptr<Integrator> make(const json& config) {
  return builtin_registry().integrators.create(config, "/integrator");
}

std::string path_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.path();
  }
  return "(no error)";
}

// A linear rate u' = A u, counting its evaluations.
struct LinearRate {
  Eigen::MatrixXd a;
  long evaluations = 0;
  CoarseRate rate() {
    return CoarseRate{[this](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
      ++evaluations;
      dudt = a * u;
      return true;
    }};
  }
};

struct Marched {
  double error;  // max |u − exact| over the steps' ends
  long evaluations;
};

// `steps` steps of dt on u' = A u from u0, against exp(A t) u0 at every step's end.
Marched march(Integrator& integrator, CoarseRate f, long& counter, const Eigen::MatrixXd& a, const Eigen::VectorXd& u0,
              double dt, int steps) {
  Eigen::VectorXd u = u0;
  double error = 0;
  counter = 0;
  for (int s = 1; s <= steps; ++s) {
    std::string issue;
    EXPECT_TRUE(integrator.step(f, dt, u, issue)) << issue;
    const Eigen::MatrixXd at = a * (s * dt);
    const Eigen::VectorXd exact = at.exp() * u0;
    error = std::max(error, (u - exact).cwiseAbs().maxCoeff());
  }
  return {error, counter};
}

}  // namespace

// arkode_erk with method forward_euler runs ARKODE's one-stage table at the fixed step dt: each step is
// u + dt f(u), then the held entries reset, as `explicit`. On a nonlinear rate (a viscous Burgers-like system with a
// source, two held ends), 40 steps agree to 1e-14 relative: the same arithmetic (ARKODE's y + (dt·1)·f, with dt·1
// exact), so only a rounding of the update's sum could differ (measured: bit for bit).
TEST(IntegratorArkode, ForwardEulerAtTheFixedStepReproducesTheExplicitStep) {
  const int n = 8;
  const std::vector<bool> held = {true, false, false, false, false, false, false, true};
  Eigen::VectorXd held_values(n);
  held_values.setZero();
  held_values[0] = 0.25;
  held_values[n - 1] = -0.125;
  CoarseRate f{[&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
                 dudt.resize(n);
                 for (int k = 0; k < n; ++k) {
                   const double left = u[(k + n - 1) % n], right = u[(k + 1) % n];
                   dudt[k] = -u[k] * (right - left) / 0.2 + 0.05 * (right - 2 * u[k] + left) / 0.01 + std::sin(u[k]);
                 }
                 return true;
               },
               &held, &held_values};
  auto explicit_euler = make(json{{"name", "explicit"}});
  auto arkode = make(json{{"name", "arkode_erk"}, {"method", "forward_euler"}});
  Eigen::VectorXd a(n), b(n);
  for (int k = 0; k < n; ++k) a[k] = std::cos(0.7 * k);  // the held entries start away from their values
  b = a;
  const double dt = 0.01;
  for (int s = 0; s < 40; ++s) {
    std::string issue;
    ASSERT_TRUE(explicit_euler->step(f, dt, a, issue)) << issue;
    ASSERT_TRUE(arkode->step(f, dt, b, issue)) << issue;
    ASSERT_LE((a - b).cwiseAbs().maxCoeff(), 1e-14 * a.cwiseAbs().maxCoeff()) << "step " << s;
  }
  EXPECT_EQ(b[0], 0.25);
  EXPECT_EQ(b[n - 1], -0.125);
  std::printf("forward Euler through ARKODE against explicit after 40 steps: max difference %.3g\n",
              (a - b).cwiseAbs().maxCoeff());
}

// Adaptive arkode_erk on u' = λu (λ = −3, u(0) = 1, ten steps of 0.1): ARKODE keeps each internal step's estimated
// local error within rtol·|u| + atol (its WRMS norm <= 1). The problem contracts (|e^{λh}| < 1), so the global error
// is at most the sum of the local errors: at most (internal steps)·(rtol·max|u| + atol), and the internal steps are
// fewer than the rate's evaluations. That bound holds with the estimate of the embedded (lower-order) solution
// standing for the error of the propagated (higher-order) one, which it overestimates on a smooth problem. Tightening
// rtol from 1e-4 to 1e-8 shrinks the error by more than 10 for every pair (measured: 100 to 10^4; not step by step:
// at rtol 1e-4 the fifth-order pair's internal steps are set by the coarse step 0.1, its error 2.9e-7 below what the
// tolerance allows, and 6.1e-8 at 1e-6).
TEST(IntegratorArkode, AdaptiveErkMeetsTheExactDecayWithinItsTolerances) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Constant(1, 1, -3.0);
  const Eigen::VectorXd u0 = Eigen::VectorXd::Ones(1);
  for (const std::string method : {"zonneveld", "heun_euler", "bogacki_shampine", "dormand_prince"}) {
    double loosest = 0, error = 0;
    for (const double rtol : {1e-4, 1e-6, 1e-8}) {
      LinearRate r{a};
      auto integrator = make(json{{"name", "arkode_erk"}, {"method", method}, {"rtol", rtol}, {"atol", 1e-14}});
      const Marched m = march(*integrator, r.rate(), r.evaluations, a, u0, 0.1, 10);
      const double bound = static_cast<double>(m.evaluations) * (rtol * 1.0 + 1e-14);
      std::printf("arkode_erk %-16s rtol %.0e: max error %.3e, %ld evaluations, bound %.3e\n", method.c_str(), rtol,
                  m.error, m.evaluations, bound);
      EXPECT_LE(m.error, bound) << method << " rtol " << rtol;
      if (loosest == 0) loosest = m.error;
      error = m.error;
    }
    EXPECT_LT(error, loosest / 10) << method;
  }
}

// A stiff 2×2 linear system u' = (S + N) u with the split offered: S symmetric with eigenvalues −1 and −1999 (the
// stiff, "viscous" part), N a slow rotation (the explicit part); u(0) = (1, 0.5), ten steps of 0.1, against
// exp((S + N) t) u0. arkode_imex (and, without the split, its DIRK alone) meets the exact solution within
// (internal steps)·(rtol·max|u| + atol), the bound above (the system is contractive in the 2-norm: S + Sᵀ and N + Nᵀ
// negative semi-definite, and the max norm is within √2 of it, taken into the factor 2), the internal steps fewer
// than the explicit part's evaluations; and tightening rtol by 1000 shrinks the error by more than 10. arkode_erk
// needs the explicit stability bound h < ~3/1999 on the same system: the IMEX run evaluates the explicit part at
// least ten times less often.
TEST(IntegratorArkode, ImexOnAStiffSplitSystemMeetsTheExactSolution) {
  Eigen::MatrixXd s(2, 2), nonstiff(2, 2);
  s << -1000, 999, 999, -1000;
  nonstiff << 0, 0.5, -0.5, 0;
  const Eigen::MatrixXd a = s + nonstiff;
  Eigen::VectorXd u0(2);
  u0 << 1, 0.5;
  const double umax = 1.0;  // the solution decays from max|u0| = 1
  long explicit_evaluations = 0, stiff_evaluations = 0;
  auto split_rate = [&]() {
    CoarseRate f{[&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
      dudt = a * u;
      return true;
    }};
    f.stiff = [&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
      ++stiff_evaluations;
      dudt = s * u;
      return true;
    };
    f.nonstiff = [&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
      ++explicit_evaluations;
      dudt = nonstiff * u;
      return true;
    };
    return f;
  };
  long imex_explicit = 0;
  for (const std::string method : {"ark436", "ark324", "ark548"}) {
    double loosest = 0;
    for (const double rtol : {1e-4, 1e-7}) {
      auto integrator = make(json{{"name", "arkode_imex"}, {"method", method}, {"rtol", rtol}, {"atol", 1e-14}});
      stiff_evaluations = 0;
      const Marched m = march(*integrator, split_rate(), explicit_evaluations, a, u0, 0.1, 10);
      const double bound = 2.0 * static_cast<double>(m.evaluations) * (rtol * umax + 1e-14);
      std::printf("arkode_imex %s rtol %.0e: max error %.3e, %ld explicit and %ld implicit evaluations, bound %.3e\n",
                  method.c_str(), rtol, m.error, m.evaluations, stiff_evaluations, bound);
      EXPECT_LE(m.error, bound) << method << " rtol " << rtol;
      if (loosest == 0) {
        loosest = m.error;
      } else {
        EXPECT_LT(m.error, loosest / 10) << method;
      }
      if (method == "ark436" && rtol == 1e-4) imex_explicit = m.evaluations;
    }
  }
  // Without the split the whole rate is implicit (the DIRK table): the same bound, counting the rate's
  // evaluations (more than the internal steps: Newton and GMRES's J·v each evaluate it).
  {
    LinearRate r{a};
    auto integrator = make(json{{"name", "arkode_imex"}, {"rtol", 1e-6}, {"atol", 1e-14}});
    const Marched m = march(*integrator, r.rate(), r.evaluations, a, u0, 0.1, 10);
    std::printf("arkode_imex without a split: max error %.3e, %ld evaluations\n", m.error, m.evaluations);
    EXPECT_LE(m.error, 2.0 * static_cast<double>(m.evaluations) * (1e-6 * umax + 1e-14));
  }
  // arkode_erk on the same system at the same tolerance: held to its stability bound.
  {
    LinearRate r{a};
    auto integrator = make(json{{"name", "arkode_erk"}, {"rtol", 1e-4}, {"atol", 1e-14}});
    const Marched m = march(*integrator, r.rate(), r.evaluations, a, u0, 0.1, 10);
    std::printf("arkode_erk on the stiff system: max error %.3e, %ld evaluations (IMEX explicit: %ld)\n", m.error,
                m.evaluations, imex_explicit);
    EXPECT_GT(m.evaluations, 10 * imex_explicit);
  }
}

// linear_solver dense on the same stiff split system: the stiff part's Jacobian probed once (n + 2 = 4 evaluations:
// the base, two unit vectors, the affinity check), each Newton system solved by the LU of I − γ J. It meets the exact
// solution within the same bound as GMRES, at each tolerance and table; and its stiff evaluations are fewer than
// GMRES's (no difference-quotient J·v products), at the same explicit ones within a factor 2 (the same error
// control on the same steps; the Newton iterations' counts may differ).
TEST(IntegratorArkode, ImexDenseMeetsTheExactSolutionWithTheProbedJacobian) {
  Eigen::MatrixXd s(2, 2), nonstiff(2, 2);
  s << -1000, 999, 999, -1000;
  nonstiff << 0, 0.5, -0.5, 0;
  const Eigen::MatrixXd a = s + nonstiff;
  Eigen::VectorXd u0(2);
  u0 << 1, 0.5;
  long explicit_evaluations = 0, stiff_evaluations = 0;
  CoarseRate f{[&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
    dudt = a * u;
    return true;
  }};
  f.stiff = [&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
    ++stiff_evaluations;
    dudt = s * u;
    return true;
  };
  f.nonstiff = [&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
    ++explicit_evaluations;
    dudt = nonstiff * u;
    return true;
  };
  for (const std::string method : {"ark436", "ark324", "ark548"})
    for (const double rtol : {1e-4, 1e-7}) {
      long stiff[2] = {0, 0}, expl[2] = {0, 0};
      for (int dense = 0; dense < 2; ++dense) {
        auto integrator = make(json{{"name", "arkode_imex"}, {"method", method}, {"rtol", rtol}, {"atol", 1e-14},
                                    {"linear_solver", dense ? "dense" : "gmres"}});
        EXPECT_EQ(integrator->needs_linear_closure(), dense == 1);
        EXPECT_FALSE(integrator->needs_affine_rate());
        stiff_evaluations = 0;
        const Marched m = march(*integrator, f, explicit_evaluations, a, u0, 0.1, 10);
        const double bound = 2.0 * static_cast<double>(m.evaluations) * (rtol + 1e-14);
        std::printf("arkode_imex %s %s rtol %.0e: max error %.3e (bound %.3e), %ld explicit, %ld implicit evaluations\n",
                    method.c_str(), dense ? "dense" : "gmres", rtol, m.error, bound, m.evaluations, stiff_evaluations);
        EXPECT_LE(m.error, bound) << method << " rtol " << rtol << (dense ? " dense" : " gmres");
        stiff[dense] = stiff_evaluations;
        expl[dense] = m.evaluations;
      }
      EXPECT_LT(stiff[1], stiff[0]) << method << " rtol " << rtol;
      EXPECT_LE(expl[1], 2 * expl[0]) << method << " rtol " << rtol;
    }
}

// linear_solver dense refuses an implicit part that is not affine (its probe's check at a second point), saying so and
// naming the way out; a model's failing rate during the probe is reported with its words. With dense, a Krylov
// closure is refused at validation (check_implicit_closure), as for backward Euler.
TEST(IntegratorArkode, ImexDenseRefusesANonAffineImplicitPart) {
  CoarseRate f{[](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
    dudt = -u.array().cube().matrix();
    return true;
  }};
  f.stiff = f.at;
  auto integrator = make(json{{"name", "arkode_imex"}, {"linear_solver", "dense"}});
  Eigen::VectorXd u = Eigen::VectorXd::Ones(3);
  std::string issue;
  EXPECT_FALSE(integrator->step(f, 0.1, u, issue));
  EXPECT_NE(issue.find("affine"), std::string::npos) << issue;
  EXPECT_NE(issue.find("linear_solver gmres"), std::string::npos) << issue;
  CoarseRate failing{[](const Eigen::VectorXd&, Eigen::VectorXd&, std::string& why) {
    why = "the closure diverged";
    return false;
  }};
  issue.clear();
  EXPECT_FALSE(make(json{{"name", "arkode_imex"}, {"linear_solver", "dense"}})->step(failing, 0.1, u, issue));
  EXPECT_NE(issue.find("the closure diverged"), std::string::npos) << issue;
  const Registry& reg = builtin_registry();
  const json solver = {{"time_integration", resolve_time_integration(
                                                reg, json{{"name", "arkode_imex"}, {"linear_solver", "dense"}},
                                                "/base/solver/time_integration")}};
  EXPECT_EQ(path_of([&] {
              check_implicit_closure(solver, *make_integrator(reg, solver, "/base"), json{{"name", "cgls"}}, "/base");
            }),
            "/base/solver/time_integration");
  EXPECT_EQ(path_of([&] {
              resolve_time_integration(reg, json{{"name", "arkode_imex"}, {"linear_solver", "lu"}},
                                       "/base/solver/time_integration");
            }),
            "/base/solver/time_integration/linear_solver");
}

// u' = λu split as λ = λ_s + λ_n (λ_s = −50 implicit, λ_n = −1 explicit), `nonstiff` not given: the explicit part is
// at − stiff. Same bound as above (a scalar contraction: factor 1).
TEST(IntegratorArkode, ImexWithoutANonstiffPartTakesTheRateLessTheStiffPart) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Constant(1, 1, -51.0);
  const Eigen::VectorXd u0 = Eigen::VectorXd::Ones(1);
  long evaluations = 0;
  CoarseRate f{[&](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
    ++evaluations;
    dudt = -51.0 * u;
    return true;
  }};
  f.stiff = [](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
    dudt = -50.0 * u;
    return true;
  };
  auto integrator = make(json{{"name", "arkode_imex"}, {"rtol", 1e-6}, {"atol", 1e-14}});
  const Marched m = march(*integrator, f, evaluations, a, u0, 0.02, 10);
  EXPECT_GT(m.evaluations, 0);  // the explicit part was evaluated through `at`
  EXPECT_LE(m.error, static_cast<double>(m.evaluations) * 1e-6);
}

// A held entry keeps its value through the adaptive step (its rate is zero during the step, then it is reset).
TEST(IntegratorArkode, HeldEntriesStayAtTheirValues) {
  const std::vector<bool> held = {true, false};
  Eigen::VectorXd held_values(2);
  held_values << 2.0, 0.0;
  CoarseRate f{[](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string&) {
                 dudt.resize(2);
                 dudt << 5.0, u[0] - u[1];  // the held entry's own rate is ignored
                 return true;
               },
               &held, &held_values};
  for (const json& config : {json{{"name", "arkode_erk"}}, json{{"name", "arkode_imex"}},
                             json{{"name", "arkode_imex"}, {"linear_solver", "dense"}}}) {
    json c = config;
    c["rtol"] = 1e-10;
    c["atol"] = 1e-14;
    auto integrator = make(c);
    const std::string name = c.dump();
    Eigen::VectorXd u(2);
    u << 2.0, 0.0;
    for (int s = 0; s < 5; ++s) {
      std::string issue;
      ASSERT_TRUE(integrator->step(f, 0.2, u, issue)) << issue;
    }
    EXPECT_EQ(u[0], 2.0) << name;
    // u1' = 2 − u1 from 0: 2 (1 − e^{−t}) at t = 1, to the tolerance (bound as above with a generous count).
    EXPECT_NEAR(u[1], 2.0 * (1 - std::exp(-1.0)), 1e-7) << name;
  }
}

// A failing rate: step() returns false, its issue naming ARKODE's flag and the model's words.
TEST(IntegratorArkode, AFailingRateIsReportedWithTheFlagName) {
  CoarseRate f{[](const Eigen::VectorXd&, Eigen::VectorXd&, std::string& issue) {
    issue = "the closure diverged";
    return false;
  }};
  for (const char* name : {"arkode_erk", "arkode_imex"}) {
    auto integrator = make(json{{"name", name}});
    Eigen::VectorXd u = Eigen::VectorXd::Ones(3);
    std::string issue;
    EXPECT_FALSE(integrator->step(f, 0.1, u, issue)) << name;
    EXPECT_NE(issue.find("ARK_"), std::string::npos) << issue;
    EXPECT_NE(issue.find("the closure diverged"), std::string::npos) << issue;
    EXPECT_FALSE(integrator->needs_affine_rate());
  }
}

// The spec path: solver.time_integration a name or {"name", parameters}; names without parameters resolve as
// before (a string: stored rows and cell ids unchanged), the ARKODE ones to their full parameters; bad parameters
// and unknown names refused at their JSON path; the ARKODE ones pass check_implicit_closure with a Krylov closure.
TEST(IntegratorArkode, TimeIntegrationIsANameOrAnObjectCheckedAtItsPath) {
  const Registry& reg = builtin_registry();
  const std::string at = "/base/solver/time_integration";
  EXPECT_EQ(resolve_time_integration(reg, "explicit", at), json("explicit"));
  EXPECT_EQ(resolve_time_integration(reg, json{{"name", "backward_euler"}}, at), json("backward_euler"));
  const json erk = resolve_time_integration(reg, "arkode_erk", at);
  EXPECT_EQ(erk.at("method"), "zonneveld");
  EXPECT_EQ(erk.at("rtol"), 1e-6);
  const json imex = resolve_time_integration(reg, json{{"name", "arkode_imex"}, {"rtol", 1e-8}}, at);
  EXPECT_EQ(imex.at("rtol"), 1e-8);
  EXPECT_EQ(imex.at("method"), "ark436");
  EXPECT_EQ(path_of([&] { resolve_time_integration(reg, json{{"name", "arkode_erk"}, {"method", "rk45"}}, at); }),
            at + "/method");
  EXPECT_EQ(path_of([&] { resolve_time_integration(reg, json{{"name", "arkode_erk"}, {"rtol", -1e-6}}, at); }),
            at + "/rtol");
  EXPECT_EQ(path_of([&] { resolve_time_integration(reg, json{{"name", "arkode_imex"}, {"tol", 1}}, at); }), at + "/tol");
  EXPECT_EQ(path_of([&] { resolve_time_integration(reg, json{{"name", "rk4"}}, at); }), at + "/name");
  EXPECT_EQ(path_of([&] { resolve_time_integration(reg, "rk4", at); }), at);
  EXPECT_EQ(path_of([&] { resolve_time_integration(reg, json{{"method", "x"}}, at); }), at);
  const json solver = {{"time_integration", imex}};
  EXPECT_EQ(integrator_name(solver), "arkode_imex");
  auto integrator = make_integrator(reg, solver, "/base");
  EXPECT_NO_THROW(check_implicit_closure(solver, *integrator, json{{"name", "cgls"}}, "/base"));
}

// End to end: the 1D quick spec (experiments/quick/channel.json, its first cell: the paper's formulation with the
// zero-order Landweber closure) through the reduced_model kind, without the direct reference, to t = 0.5 (a
// transient, far from steady). arkode_erk with forward_euler is the explicit run to round-off (the same steps; 1e-12
// relative leaves room for the rounding of a run's hundreds of steps). The adaptive arkode_erk (rtol 1e-8) is the
// ODE's solution to about 1e-8; forward Euler's own error is first order in dt, estimated by Richardson from the
// explicit runs at kappa and kappa/2 as 2·|v(κ/2) − v(κ)|: the adaptive run lies within that estimate (1.5x) of the
// explicit one, and nearer the extrapolated 2 v(κ/2) − v(κ) than the explicit run is.
TEST(IntegratorArkode, TheQuickChannelSpecAgreesWithTheExplicitStep) {
  const Registry& reg = builtin_registry();
  std::ifstream in(std::string(CLOSURELAB_SOURCE_DIR) + "/experiments/quick/channel.json");
  ASSERT_TRUE(in.good());
  const json spec = json::parse(in);
  json cell = spec.at("base");
  cell["closure"]["deconvolver"] = spec.at("cells").at(0).at("closure.deconvolver");
  cell["reference"] = {{"direct_sph", false}};
  cell["timing"] = {{"min_repeats", 1}, {"max_repeats", 1}};
  cell["solver"]["mode"] = "target_time";
  cell["solver"]["target_time"] = 0.5;
  const ExperimentKind& kind = reg.experiments.get(spec.at("kind").get<std::string>(), "");
  auto run = [&](const json& time_integration, double kappa_factor) {
    json c = cell;
    c["solver"]["time_integration"] = time_integration;
    c["solver"]["kappa"] = kind.resolve(cell, "", reg).at("solver").at("kappa").get<double>() * kappa_factor;
    const json resolved = kind.resolve(c, "", reg);
    const json row = kind.run(resolved, reg, [](const std::string&) {});
    EXPECT_EQ(row.at("status"), "ok") << row.dump().substr(0, 400);
    const std::vector<double> v = row.at("profile").at("reduced").get<std::vector<double>>();
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
  };
  const Eigen::VectorXd expl = run("explicit", 1.0), half = run("explicit", 0.5);
  const Eigen::VectorXd fe = run(json{{"name", "arkode_erk"}, {"method", "forward_euler"}}, 1.0);
  const Eigen::VectorXd erk = run(json{{"name", "arkode_erk"}, {"rtol", 1e-8}, {"atol", 1e-14}}, 1.0);
  const double scale = expl.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0);
  EXPECT_LE((fe - expl).cwiseAbs().maxCoeff(), 1e-12 * scale);
  const double euler_error = 2 * (half - expl).cwiseAbs().maxCoeff();
  const Eigen::VectorXd extrapolated = 2 * half - expl;
  std::printf("quick channel at t = 0.5: |forward_euler - explicit| %.3g, |erk - explicit| %.3g, Euler's error "
              "(Richardson) %.3g, |erk - extrapolated| %.3g, peak %.3g\n",
              (fe - expl).cwiseAbs().maxCoeff(), (erk - expl).cwiseAbs().maxCoeff(), euler_error,
              (erk - extrapolated).cwiseAbs().maxCoeff(), scale);
  EXPECT_LE((erk - expl).cwiseAbs().maxCoeff(), 1.5 * euler_error);
  EXPECT_LT((erk - extrapolated).cwiseAbs().maxCoeff(), (expl - extrapolated).cwiseAbs().maxCoeff());
}
