// The taylor-green scene's perturbed start (`perturbation`, core/base/numpy_uniform.hpp) against the particles PySPH
// 1.0b1's taylor_green.py --perturb 0.3 creates (committed: tests/peer/data/taylor_green_start_pysph_n16_perturb0.3.txt,
// written by `/usr/bin/python3 scripts/peer_taylor_green.py --start-only FILE --nx 16 --perturb 0.3 --hdx 1.5`), so a
// peer run with --perturb starts from the engine's own particles: same order, positions and velocities to round-off.
// PySPH's lattice is numpy.arange(dx/2, L, dx) (dx/2 + i dx) where the engine's is (i + 1/2) dx, so the positions
// may part in their last bit; the random shifts themselves are numpy's to the bit (test_taylor_green_perturbation).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "tests/peer/reference_file_support.hpp"

using namespace closurelab;

TEST(TaylorGreenPeerStart, PerturbedStartEqualsPySphsToRoundOff) {
  std::vector<double> x, y, u, v;
  for (const auto& r : closurelab::testing::read_xyuv_rows(std::string(CLOSURELAB_SOURCE_DIR) +
                                               "/tests/peer/data/taylor_green_start_pysph_n16_perturb0.3.txt"))
    x.push_back(r[0]), y.push_back(r[1]), u.push_back(r[2]), v.push_back(r[3]);
  const auto scene = builtin_registry().scenes.create(
      {{"name", "taylor-green"}, {"n", 16}, {"perturbation", 0.3}, {"h_over_dx", 1.5}}, "/scene");
  const ParticleSystem ps = scene->make_particles();
  ASSERT_EQ(ps.size(), x.size());
  double dpos = 0.0, dvel = 0.0, shift = 0.0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    dpos = std::max({dpos, std::abs(ps.x[a] - x[a]), std::abs(ps.y[a] - y[a])});
    dvel = std::max({dvel, std::abs(ps.vx[a] - u[a]), std::abs(ps.vy[a] - v[a])});
    // Off the lattice: each particle is shifted (by up to 0.3 spacings), so the comparison is not of two lattices.
    const int i = static_cast<int>(a % 16), j = static_cast<int>(a / 16);
    shift = std::max({shift, ps.x[a] - (i + 0.5) * scene->dx, ps.y[a] - (j + 0.5) * scene->dx});
  }
  std::printf("largest difference: positions %.3g, velocities %.3g; largest shift %.3g spacings\n", dpos, dvel,
              shift / scene->dx);
  EXPECT_GT(shift, 0.2 * scene->dx);
  EXPECT_LE(dpos, 2.3e-16);  // one ulp at 1
  EXPECT_LE(dvel, 1e-15);  // measured: positions 0 (bit for bit), velocities 3.3e-16 (numpy's sin, cos against libm's)
}
