// The cylinder-lattice scene (periodic square array, the porous-medium scene) and its reference permeability: our boundary-collocation Stokes solve
// of the square array against Sangani & Acrivos's (1982) table and against the Hasimoto / Sangani–Acrivos
// low-concentration series, its convergence in the number of harmonics; the scene's particles, reference and bad
// input.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/registry.hpp"
#include "core/scenes/square_array_stokes.hpp"
#include "core/sph/scene.hpp"
#include "tests/support/config_error.hpp"

using namespace closurelab;
using closurelab::test_support::config_error;

namespace {

double radius_for(double c) { return std::sqrt(c / M_PI); }

std::unique_ptr<Scene> lattice(json p) {
  p["name"] = "cylinder-lattice";
  return builtin_registry().scenes.create(p, "/scene");
}

}  // namespace

// Sangani & Acrivos (1982), square arrays: F/(mu U) against c (as reproduced in the Basilisk test case
// sangani.c). The table prints 4-5 digits; the solve must agree to half a unit of the last printed digit,
// except at c = 0.3 where it gives 102.881 against the printed 102.90 (1.8e-4): the solve is converged there to
// 1e-8 (next test) with a boundary residual of 3e-10, so we take the printed entry to be S&A's own truncation and
// allow 2e-4 for it (a thousandth of the 1 % the SPH target is judged at).
TEST(SquareArrayStokes, ReproducesSanganiAcrivosTable) {
  const struct {
    double c, drag, tolerance;
  } table[] = {{0.05, 15.56, 0.005 / 15.56}, {0.10, 24.83, 0.005 / 24.83},   {0.20, 51.53, 0.005 / 51.53},
               {0.30, 102.90, 2e-4},         {0.40, 217.89, 0.005 / 217.89}, {0.50, 532.55, 0.005 / 532.55}};
  for (const auto& row : table) {
    const SquareArrayStokesResult r = square_array_stokes(radius_for(row.c), 32);
    std::cout << "c = " << row.c << ": collocation " << r.drag << ", table " << row.drag << ", residual "
              << r.boundary_residual << "\n";
    EXPECT_NEAR(r.drag / row.drag - 1.0, 0.0, row.tolerance) << "c = " << row.c;
    EXPECT_NEAR(r.permeability * r.drag, 1.0, 1e-15);
  }
}

// Converged in the number of harmonics: 24 and 32 odd harmonics agree to 1e-7 up to c = 0.4 (a = 0.357 L) and
// the boundary conditions hold to 1e-6 of the flux, for the two radii of the cylinder tables (a = 0.2 L, 0.3 L) too.
TEST(SquareArrayStokes, ConvergedInTheHarmonics) {
  for (const double a : {0.05, 0.1, 0.2, 0.25, 0.3, radius_for(0.4)}) {
    const SquareArrayStokesResult r24 = square_array_stokes(a, 24), r32 = square_array_stokes(a, 32);
    EXPECT_NEAR(r24.drag / r32.drag - 1.0, 0.0, 1e-7) << "a/L = " << a;
    EXPECT_LT(r32.boundary_residual, 1e-6) << "a/L = " << a;
  }
}

// The series F/(mu U) = 4 pi / D(c), D = -1/2 ln c - 0.738 + c - 0.887 c^2 + 2.038 c^3, against the solve where it
// is valid. Its error has two parts: the printed coefficients' rounding (half a unit of the third decimal each:
// 5e-4 (1 + c^2 + c^3) in D) and the truncation, taken as the size of the last term kept (2.038 c^3, the series
// being asymptotic with terms falling at these c). Measured: 1.1e-4 at c = 0.01, 2.2e-4 at 0.05, 8.0e-4 at 0.1.
// At c = 0.3 the series is 12 % low (against the collocation solve): it is not the reference there.
TEST(SquareArrayStokes, SeriesAgreesAtLowConcentration) {
  for (const double c : {0.005, 0.01, 0.02, 0.05, 0.1}) {
    const double d = -0.5 * std::log(c) - 0.738 + c - 0.887 * c * c + 2.038 * c * c * c;
    const double tolerance = (5e-4 * (1.0 + c * c + c * c * c) + 2.038 * c * c * c) / d;
    const double solve = square_array_stokes(radius_for(c), 32).drag;
    EXPECT_NEAR(square_array_drag_series(c) / solve - 1.0, 0.0, tolerance) << "c = " << c;
  }
  const double at_03 = square_array_drag_series(0.3) / square_array_stokes(radius_for(0.3), 32).drag - 1.0;
  EXPECT_NEAR(at_03, -0.122, 0.005);
}

// The scene: the frozen particles are the lattice sites inside the cylinder. Their count N obeys
// pi (a - d)^2 <= N eps'^2 <= pi (a + d)^2 with d = eps' / sqrt 2 (the cells of the inside sites cover the disc of
// radius a - d and lie in the disc of radius a + d); the reference is the collocation solve's, and the size
// whose reference is the reference is the radius itself.
TEST(CylinderLatticeScene, FrozenSitesInsideTheCylinderAndTheReference) {
  for (const double a : {0.2, 0.3}) {
    const auto s = lattice({{"n", 48}, {"radius_over_length", a}});
    const ParticleSystem ps = s->make_particles();
    ASSERT_EQ(ps.size(), 48u * 48u);
    std::size_t solid = 0;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const bool inside = std::hypot(ps.x[p] - 0.5, ps.y[p] - 0.5) < a;
      EXPECT_EQ(static_cast<bool>(ps.fixed[p]), inside);
      solid += ps.fixed[p];
    }
    const double d = s->dx / std::sqrt(2.0), area = solid * s->dx * s->dx;
    EXPECT_GE(area, M_PI * (a - d) * (a - d));
    EXPECT_LE(area, M_PI * (a + d) * (a + d));
    ASSERT_TRUE(s->permeability.has_value());
    EXPECT_DOUBLE_EQ(s->permeability->reference, square_array_stokes(a, 32).permeability);
    EXPECT_NEAR(s->permeability->solid_fraction, M_PI * a * a, 1e-15);
    EXPECT_NEAR(s->permeability->solid_size_for(s->permeability->reference), a, 1e-9);
    EXPECT_FALSE(s->has_walls);
    EXPECT_FALSE(s->x_invariant);
  }
  // L = 2 scales k by L^2.
  const auto big = lattice({{"n", 48}, {"l", 2.0}});
  EXPECT_NEAR(big->permeability->reference / lattice({{"n", 48}})->permeability->reference, 4.0, 1e-12);
}

// Bad input names its JSON path: a cylinder that does not fit the cell (a >= L/2), a gap between cylinders that
// holds fewer than two SPH supports, a cylinder thinner than one support.
TEST(CylinderLatticeScene, BadInputNamesThePath) {
  EXPECT_NE(config_error([] {
              lattice({{"radius_over_length", 0.5}});
            }).find("/radius_over_length"),
            std::string::npos);
  EXPECT_NE(config_error([] { lattice({{"radius_over_length", 0.7}}); }).find("does not fit"), std::string::npos);
  const std::string gap = config_error([] { lattice({{"n", 48}, {"radius_over_length", 0.45}}); });
  EXPECT_NE(gap.find("/n"), std::string::npos) << gap;
  EXPECT_NE(gap.find("gap"), std::string::npos) << gap;
  EXPECT_EQ(config_error([] { lattice({{"n", 64}, {"radius_over_length", 0.45}}); }), "");  // 6.4 spacings
  const std::string thin = config_error([] { lattice({{"n", 48}, {"radius_over_length", 0.02}}); });
  EXPECT_NE(thin.find("/n"), std::string::npos) << thin;
  EXPECT_NE(thin.find("thinner"), std::string::npos) << thin;
  EXPECT_NE(config_error([] { lattice({{"g", 0.0}}); }).find("/g"), std::string::npos);
}
