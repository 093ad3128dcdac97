// The repeated timing that every reduced run and speed-up stands on (core/base/repeated_timing.hpp): the
// statistics of a list of times and the stopping rule, driven by made-up durations (no clock is read).
#include <gtest/gtest.h>

#include <vector>

#include "core/base/repeated_timing.hpp"

using namespace closurelab;

namespace {

// A run that takes the next of `times` (and the last one again once they are used up).
struct ScriptedRuns {
  std::vector<double> times;
  std::size_t next = 0;
  double operator()() { return times[std::min(next++, times.size() - 1)]; }
};

}  // namespace

TEST(RepeatedTiming, StatisticsOfOddAndEvenCounts) {
  const TimingStats odd = timing_stats({3.0, 1.0, 2.0});
  EXPECT_EQ(odd.min, 1.0);
  EXPECT_EQ(odd.median, 2.0);
  EXPECT_EQ(odd.max, 3.0);
  EXPECT_DOUBLE_EQ(odd.spread(), 1.0);
  EXPECT_DOUBLE_EQ(odd.range(), 2.0);
  EXPECT_EQ(odd.seconds, (std::vector<double>{3.0, 1.0, 2.0}));  // in the order run
  const TimingStats even = timing_stats({4.0, 1.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(even.median, 2.5);
  EXPECT_DOUBLE_EQ(even.spread(), 1.5);
  EXPECT_EQ(timing_stats({5.0}).spread(), 0.0);
}

TEST(RepeatedTiming, StopsOnceTheMinimumIsStableAfterTheLeastCount) {
  TimingPolicy p;  // 5 at least; the last 3 may lower the minimum by 2 % at most
  ScriptedRuns runs{{1.0, 1.0, 1.0, 1.0, 1.0, 1.0}};
  const TimingStats s = repeat_until_stable(std::ref(runs), p);
  EXPECT_EQ(s.repeats(), 5);
  EXPECT_EQ(s.stopped_by, "stable");
  // A minimum still falling by more than 2 % a run keeps it going until it settles (here at 0.5).
  ScriptedRuns falling{{1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.5, 0.5, 0.5}};
  const TimingStats f = repeat_until_stable(std::ref(falling), p);
  EXPECT_EQ(f.stopped_by, "stable");
  EXPECT_EQ(f.repeats(), 9);  // runs 7-9 did not lower the 0.5 of run 6
  EXPECT_EQ(f.min, 0.5);
}

TEST(RepeatedTiming, NeverMoreThanTheLargestCountNorPastTheBudget) {
  TimingPolicy p;
  p.max_repeats = 6;
  ScriptedRuns falling{{1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4}};
  const TimingStats m = repeat_until_stable(std::ref(falling), p);
  EXPECT_EQ(m.repeats(), 6);
  EXPECT_EQ(m.stopped_by, "max_repeats");
  // A run longer than the budget is timed once, and the record says why.
  p = TimingPolicy{};
  p.budget_seconds = 10.0;
  ScriptedRuns slow{{12.0}};
  const TimingStats b = repeat_until_stable(std::ref(slow), p);
  EXPECT_EQ(b.repeats(), 1);
  EXPECT_EQ(b.stopped_by, "budget");
  ScriptedRuns medium{{4.0}};
  EXPECT_EQ(repeat_until_stable(std::ref(medium), p).repeats(), 3);  // 4 + 4 + 4 >= 10
}

TEST(RepeatedTiming, SchemaDefaultsAreThePolicyDefaults) {
  const json resolved = resolve_params(json::object(), timing_schema(), "/timing", {});
  const TimingPolicy p = timing_policy_from(resolved), d;
  EXPECT_EQ(p.min_repeats, d.min_repeats);
  EXPECT_EQ(p.max_repeats, d.max_repeats);
  EXPECT_EQ(p.budget_seconds, d.budget_seconds);
  EXPECT_EQ(p.stability, d.stability);
  EXPECT_EQ(p.min_seconds, d.min_seconds);
}

TEST(RepeatedTiming, AFloorOfTimedWorkKeepsEqualRunsGoingUntilItIsSpent) {
  TimingPolicy p;
  p.min_seconds = 1.0;
  // Runs of 0.125 s agree from the start; the floor holds them to 1 s of timed work (run 8), then stable.
  ScriptedRuns equal{std::vector<double>(20, 0.125)};
  const TimingStats s = repeat_until_stable(std::ref(equal), p);
  EXPECT_EQ(s.stopped_by, "stable");
  EXPECT_EQ(s.repeats(), 8);
  // The budget still ends it first when it is the smaller.
  p.budget_seconds = 0.75;
  ScriptedRuns again{std::vector<double>(20, 0.125)};
  const TimingStats b = repeat_until_stable(std::ref(again), p);
  EXPECT_EQ(b.stopped_by, "budget");
  EXPECT_EQ(b.repeats(), 6);
}
