#pragma once
// When a repeated timing (core/base/repeated_timing.hpp) is noise: a timing whose spread, (median − min) / min,
// exceeds kNoisySpread has a minimum, and a speed-up from it, not resolved to better than that spread (load from
// other work). The run's status line says so (noisy_timing_note), and the summaries use the same threshold
// (experiments/summaries/summary_util.py, NOISY_SPREAD).
#include <string>

#include "core/base/params.hpp"

namespace closurelab {

constexpr double kNoisySpread = 0.10;

// For a row's status line: "; noisy timing: the reduced runs spread by S % (> 10 %)" when the row's
// cost.reduced_timing.spread exceeds kNoisySpread, else "".
std::string noisy_timing_note(const json& row);

}  // namespace closurelab
