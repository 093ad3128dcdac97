#pragma once
// Timing a ratio can stand on (DESIGN.md §6: a run of milliseconds timed once varies 5–20x on a shared
// machine). A timed piece of work is repeated until its minimum is stable, and the record keeps the minimum,
// the median, the largest time and their spread, so that a speed-up quotes the minimum with the spread.
//
// The stopping rule: at least `min_repeats` runs and `min_seconds` of timed work, then stop as soon as the last
// `min_repeats / 2 + 1` runs did not lower the minimum by more than `stability` (relative); never more than
// `max_repeats` runs, and no new run once `budget_seconds` of timed work is spent (so one long run is timed once,
// and says so).
#include <chrono>
#include <functional>
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {

struct TimingPolicy {
  int min_repeats = 5;
  int max_repeats = 50;
  double budget_seconds = 20.0;
  double stability = 0.02;
  // The rule does not stop as stable before this much timed work is spent, so that runs of milliseconds are
  // sampled over a stretch of the machine's load rather than a few consecutive time slices (on a loaded machine
  // a few runs can all be preempted and agree with each other; rows from before this floor ran with 0).
  double min_seconds = 0.0;
};

// The spec section "timing" of the kinds that time their work repeatedly: its schema (defaults from
// TimingPolicy{}) and the policy read from a resolved section.
ParamSchema timing_schema();
TimingPolicy timing_policy_from(const json& resolved);

struct TimingStats {
  std::vector<double> seconds;  // every run, in order
  double min = 0.0, median = 0.0, max = 0.0;
  int repeats() const { return static_cast<int>(seconds.size()); }
  // (median − min) / min: how far a typical run lies above the best one; 0 for a single run.
  double spread() const { return min > 0 ? (median - min) / min : 0.0; }
  // (max − min) / min: the whole range of the runs, the bound to quote for a ratio of minima taken at another
  // time on a shared machine (the load drifts between runs more than within one).
  double range() const { return min > 0 ? (max - min) / min : 0.0; }
  // {"repeats", "min_seconds", "median_seconds", "max_seconds", "spread", "range", "stopped_by"}
  json to_json() const;
  std::string stopped_by;  // "stable", "max_repeats" or "budget"
};

// The statistics of a list of run times (the median of an even count is the mean of the middle two).
TimingStats timing_stats(std::vector<double> seconds);

// From the first repeated timing on (repeat_until_stable calls it), the process keeps the memory it frees for
// reuse (glibc: mallopt's mmap threshold at 32 MiB, its largest, and the trim threshold at 1 GiB; elsewhere
// nothing). glibc's defaults return blocks above a few MiB to the kernel on free, so
// each repetition of a run that allocates tens of MiB (the 2D force-density model's maps: 30–40 MiB at n = 192)
// paid the page faults of fresh memory again: 30 % of its time on this machine (results/cylinders/reduced). The
// repetitions then measure the computation, as a process doing many such runs meets it; the first run still pays.
void retain_freed_memory();

// The stopping rule alone: calls `run_once` (which does the work and returns the seconds it took) until the
// policy says stop (tested with made-up durations).
TimingStats repeat_until_stable(const std::function<double()>& run_once, const TimingPolicy& policy);
// Runs `work` under `policy`, each run timed on the steady clock.
TimingStats time_repeatedly(const std::function<void()>& work, const TimingPolicy& policy);

// The CPU seconds this process has used (every thread): the cost of a piece of work in core-seconds, which, unlike
// the wall time, does not count the time the work waited while preempted on a loaded machine.
double process_cpu_seconds();

// Seconds since `t0` on the steady clock.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace closurelab
