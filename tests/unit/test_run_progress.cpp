// The progress estimate of long runs: a target-time run extrapolates its step rate; a steady run extrapolates
// the geometric decay of its change per window to the tolerance, capped by max_time.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/base/run_progress.hpp"

using closurelab::ProgressEstimate;
using closurelab::RunProgress;

TEST(RunProgress, TargetTimeFromTheStepRate) {
  RunProgress p(false, 2.0, 1e300, 1e-5);
  const ProgressEstimate e = p.update(0.5, 0.0, 10.0);  // a quarter of the model time in 10 s
  EXPECT_DOUBLE_EQ(e.fraction, 0.25);
  EXPECT_DOUBLE_EQ(e.seconds_left, 30.0);
  EXPECT_EQ(RunProgress::describe(e), "25 % done, about 30 s left");
}

TEST(RunProgress, SteadyStateFromTheDecayRateOfTheChange) {
  // change 1e-1 * 2^-k after window k, 2 s per window, tolerance 1e-5: the change reaches the tolerance when
  // 2^-k = 1e-4, k = 13.29 windows.
  RunProgress p(true, 0.0, 1e300, 1e-5);
  ProgressEstimate e = p.update(0.1, 1e-1, 2.0);
  EXPECT_LT(e.seconds_left, 0.0);  // one point: no rate yet
  for (int k = 1; k <= 5; ++k) e = p.update(0.1 * (k + 1), 1e-1 * std::pow(0.5, k), 2.0 * (k + 1));
  const double windows_left = std::log2(1e-4) * -1.0 - 5.0;
  EXPECT_NEAR(e.seconds_left, 2.0 * windows_left, 1e-9);
  EXPECT_NEAR(e.fraction, 5.0 / std::log2(1e4), 1e-12);  // log-distance covered from 1e-1 to 1e-5
}

TEST(RunProgress, SteadyStateIsCappedByMaxTime) {
  RunProgress p(true, 0.0, 1.0, 1e-5);
  p.update(0.4, 1e-1, 4.0);
  const ProgressEstimate e = p.update(0.5, 0.099, 5.0);  // barely decaying: the max-time limit comes first
  EXPECT_DOUBLE_EQ(e.seconds_left, 5.0);
  EXPECT_DOUBLE_EQ(e.fraction, 0.5);
}

// An extreme legal parameter once printed an 80-digit number of seconds left; durations are now
// in readable units.
TEST(RunProgress, DurationsAreInReadableUnits) {
  using closurelab::format_duration;
  EXPECT_EQ(format_duration(30), "30 s");
  EXPECT_EQ(format_duration(600), "10.0 min");
  EXPECT_EQ(format_duration(7200), "2.0 h");
  EXPECT_EQ(format_duration(5 * 86400), "5.0 days");
  EXPECT_EQ(format_duration(1e80), "3.17e+72 years");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::infinity()), "an unknown time");
  closurelab::ProgressEstimate e;
  e.fraction = 0.01;
  e.seconds_left = 1e80;
  EXPECT_EQ(closurelab::RunProgress::describe(e), "1 % done, about 3.17e+72 years left");
}
