// The lid-driven cavity's validation (kind direct_sph_validation on lid-driven-cavity,
// experiments/kinds/cavity_validation.hpp): the Shepard interpolation it reads the centre lines with, and the row of
// a short run (Ghia's 17 points on each centre line, the mean over the last five saved times, the particles stored at
// the 20 saved times in the reference store).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "core/base/registry.hpp"
#include "core/scenes/ghia_cavity.hpp"
#include "experiments/kinds/cavity_validation.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/reference_store.hpp"

using namespace closurelab;
namespace fs = std::filesystem;

// Shepard's normalisation reproduces a uniform field exactly (to round-off) wherever some particle is within the
// support, walls included, and gives 0 where none is.
TEST(CavityValidation, ShepardInterpolationReproducesAUniformField) {
  const auto scene = builtin_registry().scenes.create({{"name", "lid-driven-cavity"}, {"n", 16}}, "/scene");
  ParticleSystem ps = scene->make_particles();
  for (std::size_t a = 0; a < ps.size(); ++a) ps.vx[a] = 0.3, ps.vy[a] = -0.2;
  const double w = scene->cavity->origin;
  for (const auto& [x, y] : {std::pair{0.5, 0.5}, {0.0, 0.0}, {0.123, 0.987}, {1.0, 0.3}}) {
    const Vec2 v = shepard_velocity(ps, *scene, w + x, w + y);
    EXPECT_NEAR(v.x(), 0.3, 1e-15) << x << ", " << y;
    EXPECT_NEAR(v.y(), -0.2, 1e-15) << x << ", " << y;
  }
  const Vec2 far = shepard_velocity(ps, *scene, -10.0, -10.0);
  EXPECT_EQ(far.x(), 0.0);
  EXPECT_EQ(far.y(), 0.0);
}

TEST(CavityValidation, TheRowComparesTheCentreLinesWithGhiasAndStoresTheSavedTimes) {
  const fs::path store = fs::temp_directory_path() / ("closurelab_cavity_reference_" + std::to_string(::getpid()));
  fs::remove_all(store);
  const std::string before = reference_store().dir().string();
  configure_reference_store(store.string(), false);
  const Registry& reg = builtin_registry();
  const ExperimentKind& kind = reg.experiments.get("direct_sph_validation", "");
  const json cell = {{"scene", {{"name", "lid-driven-cavity"}, {"n", 16}}},
                     {"kernel", {{"name", "gaussian"}}},
                     {"solver",
                      {{"formulation", "transport_velocity"}, {"mode", "target_time"}, {"target_time", 0.2},
                       {"max_time", 0.2}}},
                     {"averaging", {{"mesh_spacing_over_eta", 0.25}}}};
  const json row = kind.run(kind.resolve(cell, "", reg), reg, [](const std::string&) {});
  configure_reference_store(before, false);
  fs::remove_all(store);
  ASSERT_EQ(row.at("status"), "ok") << row.dump();
  const json& c = row.at("errors").at("centrelines");
  const GhiaCentrelines ghia = ghia_centrelines(100.0).value();
  ASSERT_EQ(c.at("u").size(), 17u);
  ASSERT_EQ(c.at("v_end").size(), 17u);
  EXPECT_EQ(c.at("u_ghia").get<std::vector<double>>(), std::vector<double>(ghia.u.begin(), ghia.u.end()));
  EXPECT_DOUBLE_EQ(c.at("mean_over_times")[0].get<double>(), 0.16);  // saved times 0.16, 0.17, ..., 0.2
  EXPECT_DOUBLE_EQ(c.at("mean_over_times")[1].get<double>(), 0.2);
  // Early in the spin-up the flow near the lid moves with it and the rest barely does: the fluid just under the
  // lid (Ghia's y = 0.9766) is faster than at mid-height, and the largest error is that of the unformed vortex.
  EXPECT_GT(c.at("u")[1].get<double>(), c.at("u")[8].get<double>());
  EXPECT_GT(c.at("worst").get<double>(), 0.05);
  EXPECT_LE(c.at("max_abs_u").get<double>(), c.at("worst").get<double>());
  EXPECT_TRUE(std::isfinite(c.at("largest_change_between_saved_times").get<double>()));
  EXPECT_GT(row.at("errors").at("number_density").at("spread_over_mean").get<double>(), 0.0);
}
