// The repeated timing that every reduced run and speed-up stands on (core/base/repeated_timing.hpp): the
// statistics of a list of times and the stopping rule, driven by made-up durations (no clock is read).
#include <gtest/gtest.h>

#include <vector>

#include "core/base/repeated_timing.hpp"
#include "core/base/timing_noise.hpp"

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
  // The budget ends it once min_repeats runs are done: a run longer than the whole budget is still timed
  // min_repeats times (min_repeats is a true minimum), and the record says the budget stopped it.
  p = TimingPolicy{};
  p.min_repeats = 3;
  p.budget_seconds = 10.0;
  ScriptedRuns slow{{12.0, 11.0, 13.0, 10.0}};  // the minimum still falling: only the budget stops it
  const TimingStats b = repeat_until_stable(std::ref(slow), p);
  EXPECT_EQ(b.repeats(), 3);
  EXPECT_EQ(b.stopped_by, "budget");
  EXPECT_EQ(b.min, 11.0);
  p.min_repeats = 5;
  ScriptedRuns medium{{4.0, 3.0, 2.0, 1.9, 1.0, 0.5}};  // 10 s spent by run 3, yet 5 runs
  const TimingStats m5 = repeat_until_stable(std::ref(medium), p);
  EXPECT_EQ(m5.repeats(), 5);
  EXPECT_EQ(m5.stopped_by, "budget");
  // Past min_repeats the budget still ends it before the rule calls the minimum stable.
  ScriptedRuns longer{{4.0, 3.0, 2.0, 1.9, 1.0, 0.5, 0.25}};
  p.budget_seconds = 12.2;
  EXPECT_EQ(repeat_until_stable(std::ref(longer), p).repeats(), 6);  // 11.9 + 0.5 >= 12.2 at run 6
}

TEST(RepeatedTiming, ARowWhoseRunsSpreadAboveTheThresholdIsCalledNoisyInItsStatusLine) {
  const auto row = [](double spread) { return json{{"cost", {{"reduced_timing", {{"spread", spread}}}}}}; };
  EXPECT_EQ(noisy_timing_note(row(0.56)), "; noisy timing: the reduced runs spread by 56 % (> 10 %)");
  EXPECT_EQ(noisy_timing_note(row(kNoisySpread)), "");  // at the threshold: not above it
  EXPECT_EQ(noisy_timing_note(row(0.03)), "");
  EXPECT_EQ(noisy_timing_note(json{{"cost", {{"speed_up", 3.0}}}}), "");  // a row not timed repeatedly
  EXPECT_EQ(noisy_timing_note(json{{"status", "error"}}), "");
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
