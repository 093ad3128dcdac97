#pragma once
// Fraction done and time left of a long run, for its progress line. A run to a target time advances linearly in
// model time: the step rate so far gives the time left. A run to steady state stops when the relative change
// over a window falls below the tolerance; the change decays geometrically once the slowest mode dominates, so
// the decay rate per window between two updates gives the windows still needed (and the fraction done is the
// log-distance covered from the first change to the tolerance); the max-time limit caps both.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace closurelab {

// A duration for progress lines in readable units: "42 s", "3.5 min", "2.1 h", "4.2 days", "3.1e+80 years" (an
// extreme parameter once printed an 80-digit number of seconds); "an unknown time" when not finite.
inline std::string format_duration(double seconds) {
  char buf[48];
  const double s = seconds;
  if (!std::isfinite(s) || s < 0) return "an unknown time";
  if (s < 90)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 5400)
    std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else if (s < 48 * 3600.0)
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  else if (s < 730 * 86400.0)
    std::snprintf(buf, sizeof buf, "%.1f days", s / 86400);
  else
    std::snprintf(buf, sizeof buf, "%.3g years", s / (365.25 * 86400));
  return buf;
}

struct ProgressEstimate {
  double fraction = 0.0;      // in [0, 1]
  double seconds_left = -1;   // < 0: not known yet
};

class RunProgress {
 public:
  // steady: run to steady state (tolerance, give up at max_time); else run to target_time.
  RunProgress(bool steady, double target_time, double max_time, double tolerance)
      : steady_(steady), target_(target_time), max_time_(max_time), tol_(tolerance) {}

  // Called once per window: model time t, relative change over the last window, wall seconds since the start.
  ProgressEstimate update(double t, double change, double elapsed) {
    ProgressEstimate e;
    const double end = steady_ ? max_time_ : target_;
    const bool finite_end = std::isfinite(end) && end > 0 && end < 1e299;
    if (finite_end && t > 0) {  // by model time (the whole story for a target time; a cap for steady runs)
      e.fraction = std::min(1.0, t / end);
      e.seconds_left = elapsed * (end - t) / t;
    }
    if (steady_ && change > 0 && std::isfinite(change)) {
      if (first_change_ <= 0) first_change_ = change;
      if (last_change_ > 0 && elapsed > last_elapsed_ && change < last_change_) {
        const double windows_left = std::log(tol_ / change) / std::log(change / last_change_);  // per update
        const double left = std::max(0.0, windows_left) * (elapsed - last_elapsed_);
        e.seconds_left = e.seconds_left >= 0 ? std::min(e.seconds_left, left) : left;
      }
      if (first_change_ > tol_ && change < first_change_)
        e.fraction = std::max(e.fraction, std::min(1.0, std::log(first_change_ / change) / std::log(first_change_ / tol_)));
      last_change_ = change;
      last_elapsed_ = elapsed;
    }
    return e;
  }

  static std::string describe(const ProgressEstimate& e) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f %% done", 100 * e.fraction);
    return e.seconds_left < 0 ? std::string(buf) : std::string(buf) + ", about " + format_duration(e.seconds_left) + " left";
  }

 private:
  bool steady_;
  double target_, max_time_, tol_;
  double first_change_ = 0, last_change_ = 0, last_elapsed_ = 0;
};

}  // namespace closurelab
