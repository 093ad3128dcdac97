// weighted_sum_threads (core/averaging/bond_weights.hpp): a weighted sum of the stress quadratures runs on one
// thread below 2 × 32,768 bond weights, on one thread per 32,768 entries above, never on more than OpenMP allows;
// and a sum's value does not depend on how many threads computed it beyond round-off.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/averaging/bond_weights.hpp"

using namespace closurelab;

TEST(WeightedSumThreads, OneThreadForSmallSumsAndAtMostOpenMpsForLargeOnes) {
  const int most = omp_get_max_threads();
  EXPECT_EQ(weighted_sum_threads(0), 1);
  EXPECT_EQ(weighted_sum_threads(6184), 1);  // the reduced model's coarse quadrature at N/N_C = 16
  EXPECT_EQ(weighted_sum_threads(65535), 1);
  EXPECT_EQ(weighted_sum_threads(65536), std::min(2, most));
  EXPECT_EQ(weighted_sum_threads(std::size_t{1} << 40), most);
}

TEST(WeightedSumThreads, LargeTableSumsAlikeOnOneThreadAndOnAll) {
  // 40,000 bonds of 4 entries each on 64 nodes: above the one-thread limit wherever OpenMP has two threads.
  const std::size_t bonds = 40000;
  BondWeightTable table;
  table.tabulate(bonds, 64, {"xx", "xy"}, [](std::size_t p, BondWeights& w) {
    for (int k = 0; k < 4; ++k) w.emplace_back(static_cast<int>((p * 7 + k * 13) % 64), 1.0 / (1.0 + p % 97 + k));
  });
  ASSERT_EQ(table.entries(), static_cast<long>(4 * bonds));
  const auto force_and_bond = [](std::size_t p) {
    return std::make_pair(Vec2(std::sin(0.1 * p), 1.0), Vec2(1.0, std::cos(0.3 * p)));
  };
  const auto all = table.accumulate(force_and_bond);
  const int most = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = table.accumulate(force_and_bond);
  omp_set_num_threads(most);
  for (const char* c : {"xx", "xy"}) {
    const double scale = one.at(c).cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    EXPECT_LE((all.at(c) - one.at(c)).cwiseAbs().maxCoeff(), 1e-12 * scale) << c;
  }
}
