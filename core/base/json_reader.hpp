#pragma once
// Guarded JSON parsing for files a user hands to closurelab (experiment specs, stored cells): the text must be
// a regular file of bounded size, nested at most kJsonMaxDepth levels (a deeper document would overflow the
// stack in the recursive copies that follow; it is refused while parsing, before any copy), and an object may
// not repeat a key (the last one would silently win). Each refusal is a ConfigError naming the JSON path.
#include <string>

#include "core/base/params.hpp"

namespace closurelab {

inline constexpr int kJsonMaxDepth = 64;
inline constexpr long kJsonMaxBytes = 64L << 20;  // 64 MiB

// Parses `text`; `source` names it in messages.
json parse_json_guarded(const std::string& text, const std::string& source);

// The text of `file`: a regular file (checked before it is opened: a FIFO would block, /dev/zero never end) of at
// most kJsonMaxBytes, and no more than that is read. ConfigError otherwise.
std::string read_text_file_guarded(const std::string& file, long max_bytes = kJsonMaxBytes);

// Reads `file` (read_text_file_guarded) and parses it with parse_json_guarded.
json read_json_file_guarded(const std::string& file);

// A results table the runner wrote (`export`, the runner's own re-read): any size the runner can write (a 27,000-cell
// run wrote 70.8 MB), checked instead against the memory guard (memory_limit.hpp) for its text and its parsed form,
// about kJsonTableBytesPerTextByte bytes of memory per byte of text; otherwise as read_json_file_guarded.
inline constexpr double kJsonTableBytesPerTextByte = 12.0;
json read_table_file_guarded(const std::string& file);

}  // namespace closurelab
