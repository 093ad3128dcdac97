// The layered two-phase scene (§7): pair viscosity means, geometry and phases, layout scaling, and clear
// ConfigErrors (with JSON paths) for bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/errors.hpp"
#include "core/scenes/layered_scene.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_pair_force.hpp"

using namespace closurelab;

namespace {

std::unique_ptr<Scene> layered(json p) {
  p["name"] = "layered-two-phase";
  return builtin_registry().scenes.create(p, "/scene");
}

// The ConfigError thrown when building the scene, or a failure.
ConfigError scene_error(const json& p) {
  try {
    layered(p);
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no ConfigError for " << p.dump();
  return ConfigError("", "");
}

}  // namespace

TEST(PairViscosity, ArithmeticAndHarmonicMeans) {
  EXPECT_DOUBLE_EQ(pair_viscosity(100.0, 200.0, PairViscosityMean::arithmetic), 300.0);
  EXPECT_DOUBLE_EQ(pair_viscosity(100.0, 200.0, PairViscosityMean::harmonic), 4.0 * 100.0 * 200.0 / 300.0);
  EXPECT_DOUBLE_EQ(pair_viscosity(200.0, 100.0, PairViscosityMean::harmonic),
                   pair_viscosity(100.0, 200.0, PairViscosityMean::harmonic));
  // Like particles: exactly 2μ under either mean (single-phase results cannot depend on the option).
  for (double mu : {1.0, 0.1, 3.7, 200.0}) {
    EXPECT_EQ(pair_viscosity(mu, mu, PairViscosityMean::arithmetic), mu + mu);
    EXPECT_EQ(pair_viscosity(mu, mu, PairViscosityMean::harmonic), mu + mu);
  }
  // The harmonic mean never exceeds the arithmetic one and is dominated by the smaller viscosity.
  EXPECT_LT(pair_viscosity(1.0, 1e6, PairViscosityMean::harmonic), 4.0);
  EXPECT_EQ(parse_name<PairViscosityMean>("harmonic", ""), PairViscosityMean::harmonic);
  EXPECT_EQ(parse_name<PairViscosityMean>("arithmetic", ""), PairViscosityMean::arithmetic);
}

TEST(LayeredScene, GeometryPhasesAndDefaults) {
  const auto s = layered(json::object());
  EXPECT_EQ(s->params.at("case"), "case1");
  EXPECT_EQ(s->params.at("n_y"), 192);
  const double dx = 1.0 / 192, wall = 3.0 / 16;  // walls of 3η' = 36 rows outside the channel of width L = 1
  EXPECT_DOUBLE_EQ(s->dx, dx);
  EXPECT_EQ(s->ny, 192 + 2 * 36);
  EXPECT_NEAR(s->wall_lo, wall, 1e-15);
  EXPECT_NEAR(s->wall_hi - s->wall_lo, 1.0, 1e-14);
  EXPECT_NEAR(s->box.ly, 1.0 + 2.0 * wall, 1e-14);
  EXPECT_EQ(s->interfaces.size(), 10u);
  EXPECT_NEAR(s->interfaces[0], wall + 30 * dx, 1e-14);
  EXPECT_NEAR(s->interfaces[1], wall + 39 * dx, 1e-14);
  EXPECT_EQ(s->pair_viscosity_mean, PairViscosityMean::arithmetic);
  ASSERT_TRUE(s->van_der_waals.has_value());
  EXPECT_DOUBLE_EQ(s->max_viscosity(), 200.0);

  const ParticleSystem ps = s->make_particles();
  int layer_particles = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const int row = static_cast<int>(std::floor((ps.y[a] - s->wall_lo) / dx));
    const bool in_layer = (row >= 30 && row < 39) || (row >= 45 && row < 54) || (row >= 90 && row < 99) ||
                          (row >= 140 && row < 149) || (row >= 152 && row < 161);
    ASSERT_EQ(ps.phase[a], in_layer ? 1 : 0) << "row " << row;
    ASSERT_EQ(ps.fixed[a] != 0, row < 0 || row >= 192);
    EXPECT_DOUBLE_EQ(s->viscosity_at(Vec2(ps.x[a], ps.y[a])), in_layer ? 100.0 : 200.0);
    layer_particles += in_layer;
  }
  EXPECT_EQ(layer_particles, 5 * 9 * 12);
  EXPECT_DOUBLE_EQ(s->viscosity_at(Vec2(0.0, 0.01)), 200.0);  // walls: the more viscous phase
  EXPECT_EQ(layered(json{{"pair_viscosity_mean", "harmonic"}})->pair_viscosity_mean, PairViscosityMean::harmonic);
}

TEST(LayeredScene, SingleScenesKeepOnePhase) {
  const auto s = builtin_registry().scenes.create(json{{"name", "poiseuille-uniform"}}, "/scene");
  EXPECT_FALSE(s->van_der_waals.has_value());
  EXPECT_TRUE(s->interfaces.empty());
  for (int ph : s->make_particles().phase) ASSERT_EQ(ph, 0);
}

TEST(LayeredScene, PaperLayoutsScaleWithTheLattice) {
  const auto rows = [](const std::string& c, int ny) {
    json p = builtin_registry().scenes.resolve(json{{"name", "layered-two-phase"}, {"case", c}, {"n_y", ny}}, "/s");
    return layered_layout(p);
  };
  LayerLayout l = rows("case1", 192);
  EXPECT_EQ(l.start_rows, (std::vector<int>{30, 45, 90, 140, 152}));
  EXPECT_EQ(l.width, 9);
  l = rows("case1", 48);  // ×1/4, rounded
  EXPECT_EQ(l.start_rows, (std::vector<int>{8, 11, 23, 35, 38}));
  EXPECT_EQ(l.width, 2);
  l = rows("case2", 96);
  EXPECT_EQ(l.start_rows, (std::vector<int>{13, 35, 58, 80}));
  EXPECT_EQ(l.width, 5);
  l = rows("case3", 192);
  EXPECT_EQ(l.start_rows, (std::vector<int>{30, 120}));
  EXPECT_EQ(l.width, 27);
  const auto c = layered(json{{"case", "custom"}, {"n_y", 64}, {"layer_rows", {10, 40}}, {"layer_width", 5}});
  ASSERT_EQ(c->interfaces.size(), 4u);
  EXPECT_NEAR(c->interfaces[3] - c->wall_lo, 45.0 / 64, 1e-14);
}

TEST(LayeredScene, BadInputNamesItsPath) {
  EXPECT_EQ(scene_error(json{{"case", "case4"}}).path(), "/scene/case");
  EXPECT_EQ(scene_error(json{{"case", "custom"}}).path(), "/scene/layer_rows");  // no rows
  EXPECT_EQ(scene_error(json{{"case", "custom"}, {"layer_rows", {10}}}).path(), "/scene/layer_width");
  EXPECT_EQ(scene_error(json{{"case", "custom"}, {"layer_rows", {10, 14}}, {"layer_width", 4}}).path(),
            "/scene/layer_rows/1");  // touching
  EXPECT_EQ(scene_error(json{{"case", "custom"}, {"layer_rows", {10, 12}}, {"layer_width", 4}}).path(),
            "/scene/layer_rows/1");  // overlapping
  EXPECT_EQ(scene_error(json{{"case", "custom"}, {"layer_rows", {20, 10}}, {"layer_width", 4}}).path(),
            "/scene/layer_rows/1");  // not ascending
  EXPECT_EQ(scene_error(json{{"case", "custom"}, {"layer_rows", {0}}, {"layer_width", 4}}).path(),
            "/scene/layer_rows/0");  // touches the lower wall
  EXPECT_EQ(scene_error(json{{"case", "custom"}, {"layer_rows", {188}}, {"layer_width", 4}}).path(),
            "/scene/layer_rows/0");  // outside the channel
  EXPECT_EQ(scene_error(json{{"case", "custom"}, {"layer_rows", {"a"}}, {"layer_width", 4}}).path(),
            "/scene/layer_rows/0");
  EXPECT_EQ(scene_error(json{{"layer_rows", {10}}}).path(), "/scene/layer_rows");  // custom rows with case1
  EXPECT_EQ(scene_error(json{{"case", "case1"}, {"n_y", 16}}).path(), "/scene/n_y");  // width 9/12 rounds to 1,
  // but 30/12 → 3 and 45/12 → 4 touch
  EXPECT_EQ(scene_error(json{{"case", "case2"}, {"n_y", 8}}).path(), "/scene/n_y");  // layers vanish
  EXPECT_EQ(scene_error(json{{"k_star", 1.0}}).path(), "/scene/k_star");
  EXPECT_EQ(scene_error(json{{"k_star", -0.1}}).path(), "/scene/k_star");
  EXPECT_EQ(scene_error(json{{"vdw_a", 2.0}}).path(), "/scene/vdw_a");  // a_max(1/2) = 2
  EXPECT_EQ(scene_error(json{{"vdw_phi", 1.0}}).path(), "/scene/vdw_phi");
  EXPECT_EQ(scene_error(json{{"eta_over_l", 0.2}}).path(), "/scene/eta_over_l");  // 6η' > L
  EXPECT_EQ(scene_error(json{{"eta_over_l", 0.01}, {"n_y", 48}}).path(), "/scene/eta_over_l");  // walls < support
  EXPECT_EQ(scene_error(json{{"n_x", 6}}).path(), "/scene/n_x");
  EXPECT_EQ(scene_error(json{{"pair_viscosity_mean", "geometric"}}).path(), "/scene/pair_viscosity_mean");
  const std::string msg = scene_error(json{{"vdw_a", 2.5}}).what();
  EXPECT_NE(msg.find("tensile"), std::string::npos) << msg;
}
