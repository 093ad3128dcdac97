#pragma once
#include "core/base/params.hpp"

namespace closurelab {
// Git commit, version, compiler and flags, build type, UTC date, host, thread count, command line.
json provenance(const std::string& command_line);
// Peak resident memory of this process so far, in MiB (getrusage).
double peak_memory_mib();
// Writes `content` to `file` atomically (temporary file, then rename), creating parent folders.
void write_file_atomically(const std::string& file, const std::string& content);
}  // namespace closurelab
