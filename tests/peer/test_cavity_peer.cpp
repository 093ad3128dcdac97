// The lid-driven cavity (scene "lid-driven-cavity") under the transport-velocity formulation with the generalized
// wall condition (core/sph/transport_velocity.hpp) against PySPH 1.0b1's own cavity.py (TVFScheme with its solid
// walls), particle by particle: PySPH's fluid particles at t = 0.5 (440 steps at n = 20) are committed
// (tests/peer/data/cavity_pysph_n20_t0.5.txt, written by
//   /usr/bin/python3 scripts/peer_cavity.py FILE --nx 20 --tf 0.5 --pfreq 100000 -d DIR),
// and the engine steps the scene's particles from the same start with the same fixed step 0.25 h/(c0 + U), the
// last one landing on t = 0.5 as PySPH's solver lands. Paired by order (both lay the fluid row by row from the
// bottom left); the engine's coordinates are PySPH's shifted by the walls' thickness w.
//
// The tolerance, from round-off: the two codes sum each particle's neighbours in another order and write the kernel
// and the periodic-free pair vectors in algebraically equal forms, so an acceleration differs by a few ulps of its
// largest terms: the pressure terms p V² |∇W| / m ~ c² ρ dx² / h ~ 100 × 20 = 2e3 (they cancel to O(1)), so
// |δa| ~ 1e-12 per evaluation and |δv| ~ dt |δa| ~ 1e-15 per step; the flow near the lid is driven, not decaying,
// but over 0.5 time units (1/20 of the viscous time L²/ν = 100) nothing amplifies it by much: 440 steps added
// coherently give ~5e-13. Asserted: velocities within 1e-11 of the lid speed, positions within 1e-11 L. A change of
// the physics moves them by far more (measured when written: the wall's ghost velocity v_w instead of 2 v_w − ṽ_w,
// i.e. no extrapolation, planted and not committed: 0.38 U in velocity and 0.099 L in position at t = 0.5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "tests/peer/reference_file_support.hpp"

using namespace closurelab;

TEST(CavityPeer, TransportVelocityWithTheWallConditionEqualsPySphsCavityToRoundOff) {
  const auto pysph =
      closurelab::testing::read_xyuv_rows(std::string(CLOSURELAB_SOURCE_DIR) + "/tests/peer/data/cavity_pysph_n20_t0.5.txt");
  const auto scene = builtin_registry().scenes.create({{"name", "lid-driven-cavity"}, {"n", 20}}, "/scene");
  ParticleSystem ps = scene->make_particles();
  SphEngineOptions opt;
  opt.formulation = SphFormulation::transport_velocity;
  SphEngine engine(*scene, ps, opt);
  const double tf = 0.5, dt = 0.25 * scene->h / (scene->sound_speed + 1.0);  // PySPH's cavity.py: a fixed step
  const double eps = 1e-16 * tf;  // PySPH's solver: EPSILON tf, times the step count where it lands
  double t = 0.0;
  int steps = 0;
  while (tf - t > eps * (steps + 1)) {
    const double d = t + dt > tf - eps * (steps + 1) ? tf - t : dt;
    EXPECT_NEAR(engine.time_step(0.25), dt, 1e-18);
    engine.step(d);
    t += d;
    ++steps;
  }
  const double w = scene->cavity->origin;
  std::vector<std::size_t> fluid;
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) fluid.push_back(a);
  ASSERT_EQ(fluid.size(), pysph.size());
  double dpos = 0.0, dvel = 0.0, vmax = 0.0;
  for (std::size_t k = 0; k < fluid.size(); ++k) {
    const std::size_t a = fluid[k];
    const auto& [x, y, u, v] = pysph[k];
    dpos = std::max({dpos, std::abs(ps.x[a] - w - x), std::abs(ps.y[a] - w - y)});
    dvel = std::max({dvel, std::abs(ps.vx[a] - u), std::abs(ps.vy[a] - v)});
    vmax = std::max(vmax, std::hypot(u, v));
  }
  std::printf("%d steps to t = %.17g; largest difference from PySPH: positions %.3g L, velocities %.3g U (largest "
              "fluid speed %.3g U)\n", steps, t, dpos, dvel, vmax);
  EXPECT_GT(vmax, 0.1);  // the lid has set the fluid moving
  EXPECT_LE(dvel, 1e-11);
  EXPECT_LE(dpos, 1e-11);
}
