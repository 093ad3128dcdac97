// The reduced model near walls, judged as DESIGN.md §6 says: max over every coarse node (the wall-surface
// nodes included) against the averaged direct SPH of the same scene. Oracle substitution (the error budget)
// and the force-density balance with evolved wall-surface nodes.
#include <gtest/gtest.h>

#include <cmath>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/registry.hpp"
#include "core/reduced/averaged_force_map.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "experiments/kinds/experiment_kind.hpp"

using namespace closurelab;

namespace {

// One reduced_model cell on poiseuille-uniform at n_y = 48 (the direct reference comes from the reference
// store, the tests' own, so it runs once per η' in a ctest run).
json run_cell(const json& changes, double eta = 1.0 / 16) {
  const Registry& reg = builtin_registry();
  json cell = {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 48}, {"n_x", 12}, {"eta_over_ly", eta}}},
               {"closure", {{"deconvolver", {{"name", "landweber"}, {"order", 0}}}, {"discretization", "coarse_coarse"}}},
               {"quadrature", {{"name", "coarse"}, {"stride_x", 0}, {"stride_y", 4}}},
               {"solver", {{"mode", "steady"}, {"scheme", "staggered"}, {"wall_constraint_forces", true}, {"max_time", 5.0}}},
               {"reference", {{"direct_sph", true}, {"solver", {{"mode", "steady"}, {"max_time", 10}}}}}};
  cell.merge_patch(changes);
  if (changes.contains("closure") && changes["closure"].contains("deconvolver"))
    cell["closure"]["deconvolver"] = changes["closure"]["deconvolver"];  // replaced, not merged
  if (changes.contains("quadrature")) cell["quadrature"] = changes["quadrature"];
  const ExperimentKind& kind = builtin_registry().experiments.get("reduced_model", "");
  const json cfg = kind.resolve(cell, "", reg);
  return kind.run(cfg, reg, [](const std::string&) {});
}

double all_nodes_error(const json& row) {
  return row.at("errors").at("vs_averaged_direct_sph").at("all_nodes").at("max_rel").get<double>();
}

const json kForceDensity = {{"solver", {{"balance", "force_density"}, {"wall_node_value", "reconstructed"}}}};
const json kTikhonovCf = {{"closure", {{"deconvolver", {{"name", "tikhonov"}, {"alpha", 1e-6}}}, {"discretization", "coarse_fine"}}},
                          {"solver", {{"balance", "force_density"}, {"time_integration", "backward_euler"}}}};

}  // namespace

TEST(ReducedNearWall, WithEveryOracleTheSteadyStateIsTheAveragedDirectSph) {
  // The force-density balance is the exact averaged balance (2.11) (the divergence of (2.13) taken exactly, the
  // wall constraint forces included); with the closure oracle the reconstruction is exact at the direct
  // solution, so what remains is the convective stress and the direct run's own unsteadiness (steady
  // tolerance 1e-5 per 1000 steps): measured 0.08 % (cc) and 0.06 % (cf) of the peak. 0.3 % bounds them.
  json oracle = kForceDensity;
  oracle["oracle"] = {{"closure", true}};
  const json cc = run_cell(oracle);
  ASSERT_EQ(cc.at("status"), "ok");
  EXPECT_LT(all_nodes_error(cc), 3e-3);
  json cf = kTikhonovCf;
  cf["oracle"] = {{"closure", true}};
  const json rf = run_cell(cf);
  ASSERT_EQ(rf.at("status"), "ok");
  EXPECT_LT(all_nodes_error(rf), 3e-3);
  // The paper's finite-difference divergence of the stress at spacing η' is not exact: the same oracle leaves
  // an error well above the balance's (2.1 % measured with the exact quadrature and the wall nodes held).
  json fd = {{"quadrature", {{"name", "exact"}}}, {"oracle", {{"closure", true}, {"boundary", "wall_nodes"}}}};
  EXPECT_GT(all_nodes_error(run_cell(fd)), 1e-2);
}

TEST(ReducedNearWall, EvolvedWallNodesRemoveTheImposedWallValueFloor) {
  // (5.6) puts 0 where the true average is ~14 % of the peak at n_y = 48 (the floor of every closure); the
  // near-wall formulation (every node evolved by the force-density balance, coarse–fine Tikhonov with the wall
  // rows known, backward Euler) measured 0.29 %.
  const json paper = run_cell(json::object());
  ASSERT_EQ(paper.at("status"), "ok");
  EXPECT_GT(all_nodes_error(paper), 0.10);
  const json evolved = run_cell(kTikhonovCf);
  ASSERT_EQ(evolved.at("status"), "ok");
  EXPECT_LT(all_nodes_error(evolved), 0.01);
}

TEST(ReducedNearWall, ForceDensityMapEqualsTheDirectPairSweep) {
  // The force density Σ_F ψ(y_n − q_a) f_a^x applied as an affine map of the row velocities (two pair sweeps at
  // setup) against its definition from a full pair sweep of the scene's lattice carrying those velocities; both
  // wall models (the ghost wall's β depends on position only, so the force stays affine). Only rounding parts them.
  for (const char* walls : {"zero_velocity", "ghost_velocity"}) {
    SCOPED_TRACE(walls);
    const Registry& reg = builtin_registry();
    const auto scene = reg.scenes.create(json{{"name", "poiseuille-periodic"}, {"n_y", 48}, {"wall_model", walls}}, "/scene");
    const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
    const UniformMesh1D nodes{scene->wall_lo, (scene->wall_hi - scene->wall_lo) / 10, 11, false, 0.0};
    const AveragedForceMap map = fluid_force_density_map(*scene, *kernel, nodes);
    Eigen::VectorXd rows(static_cast<Eigen::Index>(map.rows.size()));
    for (Eigen::Index r = 0; r < rows.size(); ++r) rows[r] = std::sin(3.0 * map.rows[r].y()) + 0.2 * std::cos(11.0 * r);
    const Eigen::VectorXd mapped = map.apply(rows);

    ParticleSystem ps = scene->make_particles();
    for (std::size_t a = 0; a < ps.size(); ++a) {
      if (ps.fixed[a]) continue;
      for (Eigen::Index r = 0; r < rows.size(); ++r)
        if (std::abs(map.rows[r].y() - ps.y[a]) < 1e-9) ps.vx[a] = rows[r];
    }
    SphEngine engine(*scene, ps);
    std::vector<double> net(ps.size(), 0.0);
    for (const PairForce& p : engine.pair_forces()) net[p.j] += p.f.x(), net[p.k] -= p.f.x();
    Eigen::VectorXd direct = Eigen::VectorXd::Zero(nodes.count);
    for (std::size_t a = 0; a < ps.size(); ++a) {
      if (ps.fixed[a]) continue;
      double wx = 0.0;  // the column at x = 0 with its periodic images
      for (int k = -3; k <= 3; ++k) wx += kernel->factor(ps.x[a] + k * scene->box.lx);
      for (int n = 0; n < nodes.count; ++n) direct[n] += net[a] * wx * kernel->factor(nodes.node(n) - ps.y[a]);
    }
    ASSERT_GT(direct.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LT((mapped - direct).cwiseAbs().maxCoeff(), 1e-9 * direct.cwiseAbs().maxCoeff());
  }
}

TEST(ReducedNearWall, KnownZeroLandweberRunsUnderTheNearWallBalance) {
  // The paper's Landweber orders with the wall rows as known zeros (coarse–fine, lift = interpolation: the series
  // on every coarse node, the wall-surface nodes evolved and used as data, rendered on the fluid rows) run to a
  // steady state under the force-density balance with backward Euler, every node evolved (no held node). Only a
  // loose bound (50 % of the peak) is asserted: the measured figures are in results/near_wall/landweber_known_zeros.
  for (int order : {0, 2}) {
    json cell = kTikhonovCf;
    cell["closure"]["deconvolver"] = {{"name", "landweber"}, {"order", order}, {"lift", "interpolation"}};
    const json row = run_cell(cell);
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    EXPECT_LT(all_nodes_error(row), 0.5) << "order " << order;
  }
}
