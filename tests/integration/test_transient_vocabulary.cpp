// The reduced models' one transient vocabulary (experiments/kinds/reduced_sections.hpp): `transient.t_over_tau`, t / τ
// with τ the scene's time scale (Scene::time_scale()), in the column and the 2D mesh model alike; the column model's
// earlier `t_star` (t v_max / L) is read as t_over_tau, both at once is refused naming the path, and a row stored under
// the earlier name (or from before reference.file or timing.min_seconds) still matches its spec (ExperimentKind::upgraded_params), so the
// committed cells keep resuming and merging (the committed tables themselves: the ctest committed_tables_merge).
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "experiments/kinds/experiment_kind.hpp"

using namespace closurelab;

namespace {

json channel_cell(const json& transient) {
  json cell = {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 48}}},
               {"closure", {{"deconvolver", {{"name", "landweber"}, {"order", 1}}}}}};
  if (!transient.is_null()) cell["transient"] = transient;
  return cell;
}

const ExperimentKind& reduced_model() { return builtin_registry().experiments.get("reduced_model", "/kind"); }

}  // namespace

TEST(TransientVocabulary, TStarIsReadAsTOverTauInTheColumnModel) {
  const json a = reduced_model().resolve(channel_cell({{"t_star", {0.5, 1.0}}}), "/base", builtin_registry());
  const json b = reduced_model().resolve(channel_cell({{"t_over_tau", {0.5, 1.0}}}), "/base", builtin_registry());
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.at("transient"), (json{{"t_over_tau", {0.5, 1.0}}}));
}

TEST(TransientVocabulary, TheChannelsTimeScaleIsTheAdvectiveTimeAndTheCellularOneTheDecayTime) {
  const auto channel = builtin_registry().scenes.create(json{{"name", "poiseuille-uniform"}, {"n_y", 48}}, "/scene");
  EXPECT_DOUBLE_EQ(channel->time_scale(), (channel->wall_hi - channel->wall_lo) / channel->analytic_peak);
  const auto cellular = builtin_registry().scenes.create(json{{"name", "cellular"}, {"n", 48}}, "/scene");
  ASSERT_TRUE(cellular->cellular_mode.has_value());
  EXPECT_DOUBLE_EQ(cellular->time_scale(), 1.0 / cellular->cellular_mode->decay_rate);
}

TEST(TransientVocabulary, BothNamesAtOnceAreRefusedNamingThePath) {
  try {
    reduced_model().resolve(channel_cell({{"t_star", {0.5}}, {"t_over_tau", {0.5}}}), "/base", builtin_registry());
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/base/transient/t_star");
  }
}

TEST(TransientVocabulary, BadTimesAreReportedUnderTheNameTheCellUsed) {
  for (const std::string key : {"t_star", "t_over_tau"}) {
    try {
      reduced_model().resolve(channel_cell({{key, {1.0, 0.5}}}), "/base", builtin_registry());
      FAIL() << "expected a ConfigError for " << key;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.path(), "/base/transient/" + key + "/1");
    }
  }
}

TEST(TransientVocabulary, ARowStoredUnderTheEarlierNamesMatchesItsSpec) {
  const json resolved = reduced_model().resolve(channel_cell({{"t_star", {0.5}}}), "/base", builtin_registry());
  // As a row computed before the rename and before reference.file stored its parameters.
  json stored = resolved;
  stored["transient"] = {{"t_star", {0.5}}};
  stored["reference"].erase("file");
  stored["reference"].erase("step");
  stored["timing"].erase("min_seconds");
  EXPECT_NE(stored, resolved);
  EXPECT_EQ(reduced_model().upgraded_params(stored), resolved);
  // Only a rename and an inert default: other differences stay differences.
  json other = stored;
  other["reference"]["step"] = 3;
  EXPECT_NE(reduced_model().upgraded_params(other), resolved);
}
