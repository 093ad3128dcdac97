#pragma once
// Provenance (DESIGN.md §3): every row records the run that computed it; a table's header is derived from its
// rows only (the commits they came from), so re-running a matrix whose cells are all cached changes nothing.
#include <string>
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {
// This process's build and run: git commit (without the "-dirty" suffix) and dirty flag, version, compiler
// and flags, build type, UTC date, host, thread count, command line. Stored in each row it computes.
json provenance(const std::string& command_line);
// A table's provenance, derived from its rows' "provenance" objects alone: the sorted distinct commits, how many
// rows came from a dirty build, how many carry no provenance (rows written before rows recorded their own), the
// distinct compilers, build types and hosts, and the first and last date. No "now" enters it.
json table_provenance(const std::vector<json>& rows);
// Peak resident memory of this process so far, in MiB (getrusage).
double peak_memory_mib();
// Writes `content` to `file` atomically (a temporary name unique to this process and call, then rename),
// creating parent folders. Throws std::runtime_error naming the file on failure.
void write_file_atomically(const std::string& file, const std::string& content);
}  // namespace closurelab
