// The partial table was once rewritten after every cell, so a run's cost grew with the square of
// its cells (1000 trivial cells: 197 s of wall time for 32 s of cells). The schedule that now decides the
// rewrites, on a simulated clock (no timing here): cells of 1 ms whose table rewrite costs 10 us per row.
#include <gtest/gtest.h>

#include "experiments/runner/results_table.hpp"

using closurelab::PartialTableSchedule;

namespace {
struct Simulated {
  double wall = 0.0, writing = 0.0;
  int writes = 0;
};
Simulated simulate(int cells, double cell_seconds, double seconds_per_row, bool every_cell) {
  PartialTableSchedule schedule;
  Simulated s;
  for (int k = 1; k <= cells; ++k) {
    s.wall += cell_seconds;
    if (every_cell || schedule.due(s.wall)) {
      const double start = s.wall, cost = seconds_per_row * k;
      s.wall += cost;
      s.writing += cost;
      ++s.writes;
      schedule.written(start, s.wall);
    }
  }
  return s;
}
}  // namespace

TEST(PartialTableSchedule, RewritesCostAFixedFractionOfTheRun) {
  for (int cells : {1000, 10000, 100000}) {
    SCOPED_TRACE(cells);
    const double cell = 1e-3, per_row = 1e-5;
    const Simulated s = simulate(cells, cell, per_row, false);
    // At most 1/20 of the time spent since each write, plus the one write that may straddle the end.
    EXPECT_LE(s.writing, s.wall / 20.0 + per_row * cells);
    // Linear: the run costs about its cells (within the 1/20 bound and one last write).
    EXPECT_LE(s.wall, 1.06 * cells * cell + per_row * cells);
    // Every cell's rewrite (the old behaviour) is quadratic: 1000 cells cost 6x their cells, 100000 cells 500x.
    const Simulated old = simulate(cells, cell, per_row, true);
    EXPECT_GT(old.wall, 5.0 * cells * cell);
  }
}

TEST(PartialTableSchedule, TheFirstCellAtOnceThenNoRewriteBeforeTheMinimumInterval) {
  PartialTableSchedule schedule;
  EXPECT_TRUE(schedule.due(0.001));  // the first finished cell: a table that cannot be written stops the run early
  schedule.written(0.001, 0.002);
  EXPECT_FALSE(schedule.due(0.5));
  EXPECT_TRUE(schedule.due(1.1));
  schedule.written(1.0, 1.5);           // a rewrite of 0.5 s
  EXPECT_FALSE(schedule.due(1.5 + 9));  // 20 x 0.5 s must pass first
  EXPECT_TRUE(schedule.due(1.5 + 10));
}
