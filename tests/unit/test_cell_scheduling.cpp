// How the runner spreads cells: the cost-balanced shard split, the hand-out order (costliest first when several
// cells run at once), the default expected cost of a cell and the --shard syntax.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/cell_scheduler.hpp"
#include "experiments/runner/shards.hpp"

using namespace closurelab;

TEST(CellScheduling, ShardsAreCostBalancedAndTheSameForEveryCaller) {
  // Largest first, each to the least-loaded shard (by hand): 8 -> 0; 5 -> 1; 4 -> 2; 3 -> 2 (loads 8, 5, 4);
  // 2 -> 1 (loads 8, 5, 7); 1 -> 1 (loads 8, 7, 7: the first of the least). Final loads 8, 8, 7.
  const std::vector<double> costs = {1, 8, 3, 5, 4, 2};
  const std::vector<int> s = assign_shards(costs, 3);
  EXPECT_EQ(s, (std::vector<int>{1, 0, 2, 1, 2, 1}));
  EXPECT_EQ(assign_shards(costs, 3), s);
  // Equal costs: round robin in matrix order.
  EXPECT_EQ(assign_shards({1, 1, 1, 1, 1}, 2), (std::vector<int>{0, 1, 0, 1, 0}));
  EXPECT_EQ(assign_shards({1, 2}, 1), (std::vector<int>{0, 0}));
}

TEST(CellScheduling, CostliestFirstOnlyWhenSeveralRunAtOnce) {
  const std::vector<double> costs = {1, 8, 3, 8};
  EXPECT_EQ(hand_out_order({0, 1, 2, 3}, costs, 1), (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_EQ(hand_out_order({0, 1, 2, 3}, costs, 2), (std::vector<std::size_t>{1, 3, 2, 0}));  // ties: matrix order
  EXPECT_EQ(hand_out_order({0, 2}, costs, 4), (std::vector<std::size_t>{2, 0}));
}

TEST(CellScheduling, DefaultExpectedCostGrowsWithResolutionAndModelTime) {
  const ExperimentKind& kind = builtin_registry().experiments.get("direct_sph_validation", "/kind");
  auto cost = [&](int n_y, const json& solver) {
    return kind.expected_cost({{"scene", {{"n_y", n_y}}}, {"solver", solver}});
  };
  const json to_time = {{"mode", "target_time"}, {"target_time", 0.5}, {"max_time", 100.0}};
  const json steady = {{"mode", "steady"}, {"target_time", 0.5}, {"max_time", 100.0}};
  EXPECT_DOUBLE_EQ(cost(32, to_time), 32.0 * 32 * 32 * 0.5);
  EXPECT_DOUBLE_EQ(cost(32, steady), 32.0 * 32 * 32 * 100.0);
  EXPECT_DOUBLE_EQ(cost(64, to_time) / cost(32, to_time), 8.0);
  EXPECT_DOUBLE_EQ(kind.expected_cost(json::object()), 1.0);  // nothing to go by: matrix order
}

TEST(CellScheduling, ShardSyntax) {
  const Shard s = parse_shard("3/8");
  EXPECT_EQ(s.index, 3);
  EXPECT_EQ(s.count, 8);
  EXPECT_TRUE(s.active());
  EXPECT_EQ(s.text(), "3/8");
  EXPECT_EQ(parse_shard("0/1").count, 1);
  for (const char* bad :
       {"8/8", "", "3", "3/", "/8", "-1/8", "3/-8", "3/0", "03/8", "3/08", " 3/8", "3/8 ", "x/8", "1e1/20"})
    EXPECT_THROW(parse_shard(bad), ConfigError) << bad;
}
