// The force-density map probed on a particle state other than the lattice (fluid_force_density_map_at,
// core/reduced/averaged_force_map.hpp): the error budget's positions oracle, which re-probes the near-wall balance
// on the direct run's final particles (their rows slid against each other). Checked independently:
//   - on the scene's own lattice it is the strip's map (the x-average over the box against the strip's column);
//   - on a lattice whose rows have slid by arbitrary amounts in x (and jittered in y), applied to row velocities,
//     it is the engine's force pass on that state averaged by its definition, Σ_fluid φ(y_n − y_a) m (a_x − g) / l_x.
#include <gtest/gtest.h>

#include <cmath>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/registry.hpp"
#include "core/reduced/averaged_force_map.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"

using namespace closurelab;

namespace {

struct Channel {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<AveragingKernel> kernel;
  UniformMesh1D nodes;
};

Channel channel() {
  const Registry& reg = builtin_registry();
  Channel s;
  s.scene = reg.scenes.create(json{{"name", "poiseuille-periodic"}, {"n_y", 48}, {"n_x", 12}}, "/scene");
  s.kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", s.scene->eta}}, "/kernel");
  s.nodes = UniformMesh1D{s.scene->wall_lo, (s.scene->wall_hi - s.scene->wall_lo) / 10, 11, false, 0.0};
  return s;
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST(ForceDensityMapAt, OnTheLatticeItIsTheStripMap) {
  const Channel s = channel();
  const AveragedForceMap strip = fluid_force_density_map(*s.scene, *s.kernel, s.nodes);
  const AveragedForceMap at = fluid_force_density_map_at(*s.scene, *s.kernel, s.nodes, s.scene->make_particles());
  ASSERT_EQ(at.rows.size(), strip.rows.size());
  for (std::size_t r = 0; r < at.rows.size(); ++r) EXPECT_NEAR(at.rows[r].y(), strip.rows[r].y(), 1e-12);
  ASSERT_GT(max_abs(strip.map), 0.0);
  // Only rounding parts them (measured 3e-15): sums of different length, the box's 12 columns against the strip's.
  EXPECT_LT(max_abs(at.map - strip.map), 1e-12 * max_abs(strip.map));
  EXPECT_LT(max_abs(at.offset - strip.offset), 1e-12 * max_abs(strip.map));
}

TEST(ForceDensityMapAt, OnASlidLatticeItIsTheEngineForceAveraged) {
  const Channel s = channel();
  const Scene& scene = *s.scene;
  ParticleSystem ps = scene.make_particles();
  // Each fluid row slides by its own amount (up to several spacings, as a sheared run's rows do) and each particle
  // is jittered in y by up to 2 % of a spacing (a small density change, so the pressure part is not zero).
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    const double row = std::round(ps.y[a] / scene.dx - 0.5);
    ps.x[a] = std::fmod(ps.x[a] + scene.dx * (5.3 * std::sin(0.7 * row) + 0.37 * row), scene.box.lx);
    if (ps.x[a] < 0) ps.x[a] += scene.box.lx;
    ps.y[a] += 0.02 * scene.dx * std::sin(13.0 * a);
  }
  const AveragedForceMap map = fluid_force_density_map_at(scene, *s.kernel, s.nodes, ps);
  Eigen::VectorXd v(static_cast<Eigen::Index>(map.rows.size()));
  for (Eigen::Index r = 0; r < v.size(); ++r) v[r] = std::sin(3.0 * map.rows[r].y()) + 0.2 * std::cos(11.0 * r);
  const Eigen::VectorXd mapped = map.apply(v);

  for (std::size_t a = 0; a < ps.size(); ++a) {  // the fluid particles at their row's velocity
    if (ps.fixed[a]) continue;
    for (Eigen::Index r = 0; r < v.size(); ++r)
      if (std::abs(map.rows[r].y() - ps.y[a]) < 0.5 * scene.dx) ps.vx[a] = v[r];
  }
  SphEngine engine(scene, ps);
  engine.compute_accelerations();
  Eigen::VectorXd direct = Eigen::VectorXd::Zero(s.nodes.count);
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (ps.fixed[a]) continue;
    const double net = ps.mass[a] * (engine.ax()[a] - scene.force_x(ps.y[a]));
    for (int n = 0; n < s.nodes.count; ++n) direct[n] += net * s.kernel->factor(s.nodes.node(n) - ps.y[a]) / scene.box.lx;
  }
  ASSERT_GT(max_abs(direct), 0.0);
  EXPECT_LT(max_abs(mapped - direct), 1e-12 * max_abs(direct));  // measured 9e-16
  // The slid state's map is not the lattice's: the oracle measures something.
  const AveragedForceMap lattice = fluid_force_density_map(scene, *s.kernel, s.nodes);
  EXPECT_GT(max_abs(lattice.apply(v) - mapped), 1e-4 * max_abs(direct));  // measured 6e-3
}
