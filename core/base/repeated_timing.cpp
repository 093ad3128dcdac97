#include "core/base/repeated_timing.hpp"

#include "core/base/timing_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace closurelab {

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void retain_freed_memory() {
#if defined(__GLIBC__)
  static const bool done = [] {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // blocks below 32 MiB (glibc's largest threshold) from the heap
    mallopt(M_TRIM_THRESHOLD, 1 << 30);   // and the heap not trimmed until 1 GiB of it is free
    return true;
  }();
  (void)done;
#endif
}

ParamSchema timing_schema() {
  const TimingPolicy d;
  return {integer_param("min_repeats", d.min_repeats, "runs of the reduced model timed at least, whatever the budget", 1, 1000),
          integer_param("max_repeats", d.max_repeats, "runs timed at most", 1, 10000),
          number_param("budget_seconds", d.budget_seconds,
                       "no new timed run once this much timed work is spent and min_repeats runs are done (a run "
                       "longer than it is timed min_repeats times)",
                       0.0, {}, true),
          number_param("stability", d.stability,
                       "stop after min_repeats once the last min_repeats/2 + 1 runs lowered the minimum by no more "
                       "than this fraction",
                       0.0, 1.0),
          number_param("min_seconds", d.min_seconds,
                       "timed work spent at least before the minimum may be called stable (budget and max_repeats "
                       "permitting): runs of milliseconds sampled over a stretch of a loaded machine's time",
                       0.0, {})};
}

TimingPolicy timing_policy_from(const json& r) {
  TimingPolicy p;
  p.min_repeats = r.at("min_repeats").get<int>();
  p.max_repeats = std::max(p.min_repeats, r.at("max_repeats").get<int>());
  p.budget_seconds = r.at("budget_seconds").get<double>();
  p.stability = r.at("stability").get<double>();
  p.min_seconds = r.at("min_seconds").get<double>();
  return p;
}

json TimingStats::to_json() const {
  return {{"repeats", repeats()},   {"min_seconds", min}, {"median_seconds", median}, {"max_seconds", max},
          {"spread", spread()},     {"range", range()},   {"stopped_by", stopped_by}};
}

TimingStats timing_stats(std::vector<double> seconds) {
  TimingStats s;
  s.seconds = seconds;
  if (seconds.empty()) return s;
  std::sort(seconds.begin(), seconds.end());
  const std::size_t n = seconds.size();
  s.min = seconds.front();
  s.max = seconds.back();
  s.median = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
  return s;
}

// min_repeats is a true minimum: the budget ends the runs only once min_repeats are done (a run longer than the
// budget is timed min_repeats times, and the record says "budget").
TimingStats repeat_until_stable(const std::function<double()>& run_once, const TimingPolicy& policy) {
  retain_freed_memory();
  std::vector<double> seconds;
  double spent = 0.0;
  // The minimum before the last `window` runs: stable when those runs improved on it by at most `stability`.
  const int window = policy.min_repeats / 2 + 1;
  std::string stopped_by = "max_repeats";
  while (static_cast<int>(seconds.size()) < policy.max_repeats) {
    const double t = run_once();
    seconds.push_back(t);
    spent += t;
    const int n = static_cast<int>(seconds.size());
    if (n >= policy.min_repeats && n > window && spent >= policy.min_seconds) {
      const double before = *std::min_element(seconds.begin(), seconds.end() - window);
      const double now = *std::min_element(seconds.begin(), seconds.end());
      if (now >= before * (1.0 - policy.stability)) {
        stopped_by = "stable";
        break;
      }
    }
    if (n >= policy.min_repeats && spent >= policy.budget_seconds) {
      stopped_by = "budget";
      break;
    }
  }
  TimingStats s = timing_stats(std::move(seconds));
  s.stopped_by = stopped_by;
  return s;
}

std::string noisy_timing_note(const json& row) {
  const json* t = nullptr;
  if (row.is_object() && row.contains("cost") && row["cost"].is_object() && row["cost"].contains("reduced_timing"))
    t = &row["cost"]["reduced_timing"];
  if (!t || !t->is_object() || !t->contains("spread") || !(*t)["spread"].is_number()) return "";
  const double spread = (*t)["spread"].get<double>();
  if (!(spread > kNoisySpread)) return "";
  char text[120];
  std::snprintf(text, sizeof text, "; noisy timing: the reduced runs spread by %.3g %% (> %.3g %%)", 100.0 * spread,
                100.0 * kNoisySpread);
  return text;
}

TimingStats time_repeatedly(const std::function<void()>& work, const TimingPolicy& policy) {
  return repeat_until_stable(
      [&] {
        const auto t0 = std::chrono::steady_clock::now();
        work();
        return seconds_since(t0);
      },
      policy);
}

}  // namespace closurelab
