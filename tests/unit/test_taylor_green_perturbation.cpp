// The taylor-green scene's `perturbation` (Scene::position_perturbation): numpy's legacy uniform generator reproduced
// bit for bit (core/base/numpy_uniform.hpp), the particles shifted as PySPH's taylor_green.py --perturb shifts them,
// the initial velocity taken at the shifted sites, and perturbation 0 leaving the lattice bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/base/numpy_uniform.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "tests/support/config_error.hpp"

using namespace closurelab;

// /usr/bin/python3 -c "import numpy as np; np.random.seed(1); a = np.random.random(2500); print(repr(a[:3]), repr(a[-1]))"
TEST(NumpyLegacyUniform, EqualsNumpysRandomAfterSeedOne) {
  NumpyLegacyUniform u(1);
  EXPECT_EQ(u.next(), 0.417022004702574);
  EXPECT_EQ(u.next(), 0.7203244934421581);
  EXPECT_EQ(u.next(), 0.00011437481734488664);
  for (int k = 3; k < 2499; ++k) u.next();
  EXPECT_EQ(u.next(), 0.3506171893069536);
}

// PySPH: x, y = meshgrid(arange(dx/2, L, dx)) (x fastest), x += random(n²) p dx, then y += random(n²) p dx, and the
// exact velocity at the shifted sites.
TEST(TaylorGreenPerturbation, ShiftsAsPySphsPerturbAndSetsTheVelocityThere) {
  const int n = 50;
  const double p = 0.3;
  const auto scene = builtin_registry().scenes.create({{"name", "taylor-green"}, {"n", n}, {"perturbation", p}}, "/scene");
  const ParticleSystem ps = scene->make_particles();
  ASSERT_EQ(ps.size(), static_cast<std::size_t>(n * n));
  NumpyLegacyUniform u(1);
  std::vector<double> xi(n * n), zeta(n * n);
  for (double& v : xi) v = u.next();
  for (double& v : zeta) v = u.next();
  const double dx = scene->dx;
  for (int a : {0, 1, n, n * n - 1}) {
    const int i = a % n, j = a / n;
    EXPECT_DOUBLE_EQ(ps.x[a], (i + 0.5) * dx + xi[a] * p * dx) << a;
    EXPECT_DOUBLE_EQ(ps.y[a], (j + 0.5) * dx + zeta[a] * p * dx) << a;
    const Vec2 v = scene->taylor_green->velocity_at(ps.x[a], ps.y[a], 0.0);
    EXPECT_EQ(ps.vx[a], v.x()) << a;
    EXPECT_EQ(ps.vy[a], v.y()) << a;
  }
  for (std::size_t a = 0; a < ps.size(); ++a) {
    EXPECT_GE(ps.x[a], 0.0);
    EXPECT_LT(ps.x[a], 1.0);
    EXPECT_GE(ps.y[a], 0.0);
    EXPECT_LT(ps.y[a], 1.0);
  }
}

TEST(TaylorGreenPerturbation, ZeroKeepsTheLattice) {
  const auto scene = builtin_registry().scenes.create({{"name", "taylor-green"}, {"n", 25}}, "/scene");
  EXPECT_EQ(scene->position_perturbation, 0.0);
  const ParticleSystem ps = scene->make_particles();
  for (std::size_t a = 0; a < ps.size(); ++a) {
    EXPECT_EQ(ps.x[a], (static_cast<int>(a % 25) + 0.5) * scene->dx);
    EXPECT_EQ(ps.y[a], (static_cast<int>(a / 25) + 0.5) * scene->dx);
  }
}

TEST(TaylorGreenPerturbation, OutOfRangeIsAConfigError) {
  for (double p : {0.6, -0.1}) {
    const std::string message = test_support::config_error(
        [p] { builtin_registry().scenes.create({{"name", "taylor-green"}, {"perturbation", p}}, "/scene"); });
    EXPECT_NE(message.find("/scene/perturbation"), std::string::npos) << message;
  }
}
