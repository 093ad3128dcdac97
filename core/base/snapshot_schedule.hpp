#pragma once
// Snapshot times of a time-stepping run (direct SPH or the reduced model): the step before a snapshot is
// shortened to land on it exactly, and the snapshot is taken after that step. Times must be ascending.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace closurelab {

class SnapshotSchedule {
 public:
  SnapshotSchedule() = default;
  explicit SnapshotSchedule(std::vector<double> times) : times_(std::move(times)) {}

  // The step to take from `time`, no longer than `dt` and not past the next pending snapshot.
  double clamp(double time, double dt) const {
    return next_ < times_.size() ? std::min(dt, std::max(times_[next_] - time, 0.0)) : dt;
  }
  // True (once per snapshot) when `time` has reached the next pending snapshot; advances past it.
  bool due(double time) {
    if (next_ >= times_.size() || time < times_[next_] * (1.0 - 1e-12)) return false;
    ++next_;
    return true;
  }
  bool pending() const { return next_ < times_.size(); }

 private:
  std::vector<double> times_;
  std::size_t next_ = 0;
};

}  // namespace closurelab
