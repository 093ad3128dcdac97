// group_by_first_particle (core/sph/neighbour_search.hpp), the layout of the SPH engine's Verlet list: against a
// random pair list, the grouped list holds the same pairs, each row one particle i with its partners j ascending,
// and the blocks cover the rows in order, each closed once it holds at least `block_pairs` pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

#include "core/sph/neighbour_search.hpp"

using namespace closurelab;

TEST(GroupedPairList, SamePairsInRowsOfOneParticleAndBlocksInOrder) {
  const std::size_t n = 500, block = 64;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> particle(0, static_cast<int>(n) - 1);
  std::set<std::pair<int, int>> made;
  PairList list;
  while (made.size() < 6000) {
    int a = particle(rng), b = particle(rng);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    if (!made.insert({a, b}).second) continue;
    list.i.push_back(a);
    list.j.push_back(b);
  }
  const GroupedPairList g = group_by_first_particle(list, n, block);

  std::set<std::pair<int, int>> grouped;
  for (std::size_t p = 0; p < g.pairs.size(); ++p) grouped.insert({g.pairs.i[p], g.pairs.j[p]});
  EXPECT_EQ(grouped, made);
  EXPECT_EQ(g.pairs.size(), made.size());

  ASSERT_EQ(g.row_begin.size(), g.row_i.size() + 1);
  EXPECT_EQ(g.row_begin.front(), 0u);
  EXPECT_EQ(g.row_begin.back(), g.pairs.size());
  for (std::size_t r = 0; r < g.row_i.size(); ++r) {
    EXPECT_LT(g.row_begin[r], g.row_begin[r + 1]) << "an empty row " << r;
    if (r > 0) {
      EXPECT_LT(g.row_i[r - 1], g.row_i[r]);
    }
    for (std::size_t p = g.row_begin[r]; p < g.row_begin[r + 1]; ++p) {
      EXPECT_EQ(g.pairs.i[p], g.row_i[r]);
      if (p > g.row_begin[r]) {
        EXPECT_LT(g.pairs.j[p - 1], g.pairs.j[p]);
      }
    }
  }

  ASSERT_GE(g.block_row.size(), 2u);
  EXPECT_EQ(g.block_row.front(), 0u);
  EXPECT_EQ(g.block_row.back(), g.row_i.size());
  std::size_t longest = 0;
  for (std::size_t b = 0; b + 1 < g.block_row.size(); ++b) {
    const std::size_t pairs = g.row_begin[g.block_row[b + 1]] - g.row_begin[g.block_row[b]];
    longest = std::max(longest, pairs);
    if (b + 2 < g.block_row.size()) {  // every block but the last is closed at the first row reaching `block`
      EXPECT_GE(pairs, block);
      const std::size_t last_row = g.block_row[b + 1] - 1;
      EXPECT_LT(g.row_begin[last_row] - g.row_begin[g.block_row[b]], block);
    }
  }
  EXPECT_EQ(g.longest_block, longest);
}

TEST(GroupedPairList, AnEmptyListHasNoRowsAndOneEmptyBlockBoundary) {
  const GroupedPairList g = group_by_first_particle(PairList{}, 10);
  EXPECT_EQ(g.pairs.size(), 0u);
  EXPECT_TRUE(g.row_i.empty());
  EXPECT_EQ(g.row_begin, std::vector<std::uint32_t>{0u});
  EXPECT_EQ(g.block_row, std::vector<std::uint32_t>{0u});
  EXPECT_EQ(g.longest_block, 0u);
}
