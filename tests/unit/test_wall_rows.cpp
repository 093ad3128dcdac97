// A particle row on a wall surface. On poiseuille-uniform at n_y = 32, eta'/L_y = 0.078125 (3 eta'/epsilon'
// = 7.5) the row y = 7.5 epsilon' lay exactly on y = 3 eta': the engine held it as fluid (y < wall_lo false), the
// reduced model's fine mesh counted it as wall (floor(wall_lo / epsilon' - 1/2) + 1), and the near-wall formulation
// reported 9.87 % `ok` between 0.075 % and 0.029 % at its neighbours. Such a geometry is now refused, naming the key
// and the two nearest values with the surface midway between rows; everywhere else the engine's held rows and the
// reduced model's first fluid row agree, over a sweep of eta' at several n_y.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/reduced/reduced_grid.hpp"
#include "core/sph/scene.hpp"

using namespace closurelab;

namespace {

json channel(int n_y, double eta_over_ly) {
  return {{"name", "poiseuille-uniform"}, {"n_y", n_y}, {"n_x", 12}, {"eta_over_ly", eta_over_ly}};
}

}  // namespace

TEST(WallRows, TheIssuesCaseIsRefusedWithNearbyValidValues) {
  try {
    builtin_registry().scenes.create(channel(32, 0.078125), "/scene");
    FAIL() << "a row on the wall surface was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/scene/eta_over_l");
    EXPECT_NE(e.message().find("lies on the wall surface"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("0.07291666667"), std::string::npos) << e.message();  // 7 / 96
    EXPECT_NE(e.message().find("0.08333333333"), std::string::npos) << e.message();  // 8 / 96
  }
  // The reported case's neighbours, and the suggested values, are accepted.
  for (double eta : {0.0625, 0.09375, 7.0 / 96.0, 8.0 / 96.0})
    EXPECT_NO_THROW(builtin_registry().scenes.create(channel(32, eta), "/scene")) << eta;
  // The cylinder channel's walls likewise (n = 32, 3 eta'/epsilon' = 7.5).
  EXPECT_THROW(builtin_registry().scenes.create(json{{"name", "cylinder-channel"}, {"n", 32}, {"eta_over_l", 0.078125}},
                                                "/scene"),
               ConfigError);
}

// A sweep of eta' in steps of epsilon' / 12 (3 eta'/epsilon' from 6 to 9 in steps of 1/4: the half-integers, the
// integers and the values between) at n_y = 24, 32, 48, 96: each scene is refused exactly when 3 eta'/epsilon' is a half-integer,
// and every accepted one holds the same rows in the engine (Scene::make_particles' flags) as the reduced model's
// fine mesh leaves out (make_reduced_grid: its nodes are the fluid rows).
TEST(WallRows, EngineAndReducedModelAgreeOnEveryAcceptedRow) {
  int refused = 0, accepted = 0;
  for (int n_y : {24, 32, 48, 96}) {
    for (int q = 0; q <= 12; ++q) {
      const double r = 6.0 + q / 4.0;  // 3 eta' / epsilon' from 6 to 9 (walls at least the SPH support, 3 epsilon')
      const double eta_over_ly = r / (3.0 * n_y);
      const bool on_row = std::abs(r - std::floor(r) - 0.5) < 1e-12;
      SCOPED_TRACE("n_y = " + std::to_string(n_y) + ", 3 eta'/epsilon' = " + std::to_string(r));
      std::unique_ptr<Scene> scene;
      try {
        scene = builtin_registry().scenes.create(channel(n_y, eta_over_ly), "/scene");
      } catch (const ConfigError& e) {
        EXPECT_TRUE(on_row) << e.what();
        ++refused;
        continue;
      }
      EXPECT_FALSE(on_row);
      ++accepted;
      const ParticleSystem ps = scene->make_particles();
      int held_below = 0, held_above = 0;
      for (int j = 0; j < scene->ny; ++j) {
        const bool held = ps.fixed[static_cast<std::size_t>(j) * scene->nx] != 0;
        if (held && (j + 0.5) * scene->dx < 0.5 * scene->box.ly) ++held_below;
        if (held && (j + 0.5) * scene->dx > 0.5 * scene->box.ly) ++held_above;
      }
      EXPECT_EQ(held_below, held_above);  // the walls are mirror images
      const auto kernel =
          builtin_registry().kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
      const ReducedGrid g = make_reduced_grid(*scene, *kernel, 0.25, true, false);  // its fine rows do not depend on the spacing
      EXPECT_EQ(g.fine.origin, (held_below + 0.5) * scene->dx);                  // the first fluid row
      EXPECT_EQ(g.fine.count, scene->ny - held_below - held_above);                // every fluid row
    }
  }
  EXPECT_EQ(refused, 4 * 3);  // r = 6.5, 7.5, 8.5 at each n_y
  EXPECT_GT(accepted, 0);
}
