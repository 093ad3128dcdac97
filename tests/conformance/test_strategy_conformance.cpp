// Generic checkers run over every registered averaging kernel, stress quadrature and scene (DESIGN.md §2, §5,
// §7 rung 1): registering one is enough to have it checked here. The checks live in strategies/conformance/
// (GoogleTest-free) so that a user's project runs the same ones on its own strategies. About 3 s in all.
#include <gtest/gtest.h>

#include <map>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "strategies/conformance/kernel_conformance.hpp"
#include "strategies/conformance/quadrature_conformance.hpp"
#include "strategies/conformance/scene_conformance.hpp"

using namespace closurelab;

namespace {

std::vector<std::string> names_of(const FamilyBase& family) {
  std::vector<std::string> names;
  for (const auto& e : family.entries()) names.push_back(e.name);
  return names;
}

std::string test_name(const ::testing::TestParamInfo<std::string>& i) {
  std::string n = i.param;
  for (auto& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

// The finest setting of each registered quadrature (the one that is the exact pair sum); a quadrature
// registered without an entry here fails QuadratureConformance.HasAFinestSetting.
const std::map<std::string, json>& finest_settings() {
  static const std::map<std::string, json> table = {{"exact", json::object()},
                                                    {"coarse", {{"stride_x", 1}, {"stride_y", 1}}}};
  return table;
}

// Parameter sets each scene is checked with besides its defaults (other layouts, forces, viscosities).
const std::map<std::string, std::vector<json>>& scene_variants() {
  static const std::map<std::string, std::vector<json>> table = {
      {"layered-two-phase",
       {{{"case", "case2"}},
        {{"case", "case3"}, {"mu_less_viscous", 20.0}},
        {{"case", "custom"}, {"n_y", 48}, {"layer_rows", {3, 20, 40}}, {"layer_width", 4}, {"g", -2.0}}}},
      {"poiseuille-periodic", {{{"amplitude", -2.5}, {"n", 3}, {"mu", 0.3}}}},
      {"poiseuille-uniform", {{{"g", 2.0}, {"rho", 3.0}, {"mu", 0.5}, {"eta_over_ly", 0.1}}}},
      {"kolmogorov", {{{"k", 3}, {"mu", 2.0}, {"ly", 2.0}}}}};
  return table;
}

class KernelConformance : public ::testing::TestWithParam<std::string> {
 protected:
  void expect_conforms(const std::string& check) const {
    const ConformanceReport r = run_kernel_conformance(builtin_registry(), GetParam(), check);
    ASSERT_EQ(r.checks.size(), 1u) << check;
    EXPECT_TRUE(r.ok()) << r.to_string();
  }
};

class QuadratureConformance : public ::testing::TestWithParam<std::string> {
 protected:
  void expect_conforms(const std::string& check) const {
    const auto it = finest_settings().find(GetParam());
    ASSERT_NE(it, finest_settings().end()) << "no finest setting for quadrature " << GetParam();
    const ConformanceReport r = run_quadrature_conformance(builtin_registry(), GetParam(), it->second, check);
    ASSERT_EQ(r.checks.size(), 1u) << check;
    EXPECT_TRUE(r.ok()) << r.to_string();
  }
};

class SceneConformance : public ::testing::TestWithParam<std::string> {
 protected:
  void expect_conforms(const std::string& check) const {
    std::vector<json> sets{json::object()};
    if (const auto it = scene_variants().find(GetParam()); it != scene_variants().end())
      sets.insert(sets.end(), it->second.begin(), it->second.end());
    for (const json& p : sets) {
      const ConformanceReport r = run_scene_conformance(builtin_registry(), GetParam(), p, check);
      ASSERT_EQ(r.checks.size(), 1u) << check;
      EXPECT_TRUE(r.ok()) << p.dump() << "\n" << r.to_string();
    }
  }
};

}  // namespace

TEST_P(KernelConformance, WindowIsEvenNonnegativeAndSupported) { expect_conforms("window_is_even_nonnegative_and_supported"); }
TEST_P(KernelConformance, NormalizationIsOne) { expect_conforms("normalization_is_one"); }
TEST_P(KernelConformance, FourierSymbolMatchesQuadrature) { expect_conforms("fourier_symbol_matches_quadrature"); }
TEST_P(KernelConformance, BondIntegralMatchesQuadratureAndShortBondLimit) {
  expect_conforms("bond_integral_matches_quadrature_and_short_bond_limit");
}
TEST_P(KernelConformance, FactorDerivativeMatchesDifferenceQuotient) {
  expect_conforms("factor_derivative_matches_difference_quotient");
}
INSTANTIATE_TEST_SUITE_P(AllRegistered, KernelConformance, ::testing::ValuesIn(names_of(builtin_registry().kernels)), test_name);

TEST_P(QuadratureConformance, HasAFinestSetting) {
  EXPECT_TRUE(finest_settings().count(GetParam()))
      << "quadrature '" << GetParam() << "' has no finest setting: add it to finest_settings() in " << __FILE__;
}
TEST_P(QuadratureConformance, FinestSettingIsTheExactPairSum) { expect_conforms("finest_setting_is_the_exact_pair_sum"); }
TEST_P(QuadratureConformance, VirialIdentityOnAPeriodicBox) { expect_conforms("virial_identity_on_a_periodic_box"); }
TEST_P(QuadratureConformance, AffineInVelocityAndBlindToTranslation) {
  expect_conforms("affine_in_velocity_and_blind_to_translation");
}
TEST_P(QuadratureConformance, ReportsEachCall) { expect_conforms("reports_each_call"); }
INSTANTIATE_TEST_SUITE_P(AllRegistered, QuadratureConformance,
                         ::testing::ValuesIn(names_of(builtin_registry().quadratures)), test_name);

TEST_P(SceneConformance, AnalyticSolutionSatisfiesItsOde) { expect_conforms("analytic_solution_satisfies_its_ode"); }
TEST_P(SceneConformance, InterfacesCarryContinuousVelocityAndShearStress) {
  expect_conforms("interfaces_carry_continuous_velocity_and_shear_stress");
}
TEST_P(SceneConformance, WallConditionsHold) { expect_conforms("wall_conditions_hold"); }
TEST_P(SceneConformance, AnalyticPeakIsTheMaximum) { expect_conforms("analytic_peak_is_the_maximum"); }
INSTANTIATE_TEST_SUITE_P(AllRegistered, SceneConformance, ::testing::ValuesIn(names_of(builtin_registry().scenes)), test_name);

// The libraries themselves: each lists its checks, runs them all when asked for none, and refuses an unknown
// name or check with a ConfigError; a broken strategy is reported with the check and the reason.
TEST(StrategyConformanceLibrary, RunsEveryCheckAndNamesUnknownOnes) {
  const Registry& r = builtin_registry();
  EXPECT_EQ(run_kernel_conformance(r, "gaussian").checks, kernel_conformance_checks());
  EXPECT_EQ(run_scene_conformance(r, "poiseuille-uniform").checks, scene_conformance_checks());
  EXPECT_EQ(run_quadrature_conformance(r, "exact", json::object(), "reports_each_call").checks,
            std::vector<std::string>{"reports_each_call"});
  EXPECT_THROW(run_kernel_conformance(r, "no_such_kernel"), ConfigError);
  EXPECT_THROW(run_kernel_conformance(r, "gaussian", "no_such_check"), ConfigError);
  EXPECT_THROW(run_quadrature_conformance(r, "no_such_quadrature"), ConfigError);
  EXPECT_THROW(run_quadrature_conformance(r, "exact", json::array()), ConfigError);
  EXPECT_THROW(run_scene_conformance(r, "no_such_scene"), ConfigError);
  EXPECT_THROW(run_scene_conformance(r, "poiseuille-uniform", {{"n_y", -3}}), ConfigError);
}

TEST(StrategyConformanceLibrary, ReportsBrokenStrategies) {
  Registry r;
  register_builtin_strategies(r);
  // A coarse quadrature whose "finest" setting is not fine: it is not the exact pair sum.
  const ConformanceReport q = run_quadrature_conformance(r, "coarse", {{"stride_x", 0}, {"stride_y", 4}},
                                                         "finest_setting_is_the_exact_pair_sum");
  EXPECT_FALSE(q.ok());
  EXPECT_NE(q.to_string().find("coarse finest_setting_is_the_exact_pair_sum: FAILED"), std::string::npos) << q.to_string();
  // A scene whose analytic solution misses the viscosity (μ = 2 but v is the μ = 1 parabola) fails its ODE.
  r.scenes.add({"wrong-mu", "", r.scenes.info("poiseuille-uniform").params}, [&r](const json& p) {
    json q = p;
    q["name"] = "poiseuille-uniform";
    auto s = r.scenes.create(q, "/scene");
    s->phase_viscosity = {2.0};
    return s;
  });
  const ConformanceReport s = run_scene_conformance(r, "wrong-mu", json::object(), "analytic_solution_satisfies_its_ode");
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(run_scene_conformance(r, "wrong-mu", json::object(), "wall_conditions_hold").ok());
}
