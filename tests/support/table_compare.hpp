#pragma once
// Shared by the runner tests that compare two tables of the same matrix computed in different ways (threads, MPI
// ranks, shards): equal except the run's timings and provenance.
#include "core/base/params.hpp"

namespace closurelab::testing {

// `table` without what depends on the run rather than on the cells: every "provenance" object (when, where,
// threads, ranks), keys holding a time or a ratio of times ("...seconds", "..._per_second", "speed_up..."), the
// repeated timing's records (reduced_timing, direct_sph_timing), the peak
// memory, and the reference-store record of a direct reference (whether it was reused or computed, and by
// which run, depends on the schedule), at any depth.
inline json without_timings(const json& table) {
  if (table.is_array()) {
    json out = json::array();
    for (const auto& v : table) out.push_back(without_timings(v));
    return out;
  }
  if (!table.is_object()) return table;
  json out = json::object();
  for (const auto& [k, v] : table.items()) {
    if (k == "provenance" || k.find("seconds") != std::string::npos || k.find("per_second") != std::string::npos ||
        k.rfind("speed_up", 0) == 0 || k.find("peak_memory") != std::string::npos || k == "reference_store" ||
        k == "reduced_timing" || k == "direct_sph_timing")  // the repeated timing: run counts and dates vary
      continue;
    out[k] = without_timings(v);
  }
  return out;
}

}  // namespace closurelab::testing
