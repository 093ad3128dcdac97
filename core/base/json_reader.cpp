#include "core/base/json_reader.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"

namespace closurelab {

namespace {

struct Frame {
  bool object = false;
  std::set<std::string> keys;
  std::string key;  // the member being parsed (objects)
};

std::string path_of(const std::vector<Frame>& frames) {
  std::string p;
  for (const auto& f : frames) p += "/" + (f.object ? f.key : std::string("*"));
  return p;
}

}  // namespace

json parse_json_guarded(const std::string& text, const std::string& source) {
  std::vector<Frame> frames;
  auto callback = [&](int depth, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (depth >= kJsonMaxDepth)
          throw ConfigError(path_of(frames), "'" + source + "' is nested more than " + std::to_string(kJsonMaxDepth) +
                                                 " levels deep (refused before copying)");
        frames.push_back(Frame{event == json::parse_event_t::object_start, {}, {}});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!frames.empty()) frames.pop_back();
        break;
      case json::parse_event_t::key: {
        if (frames.empty()) break;
        Frame& f = frames.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw ConfigError(path_of(frames), "duplicate key '" + f.key + "' in '" + source + "'");
        break;
      }
      case json::parse_event_t::value: break;
    }
    return true;
  };
  try {
    return json::parse(text, callback);
  } catch (const json::exception& e) {  // syntax errors, and numbers that overflow (1e999)
    throw ConfigError("", "malformed JSON in '" + source + "': " + e.what());
  }
}

std::string read_text_file_guarded(const std::string& file, long max_bytes) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw ConfigError("", "cannot open '" + file + "' (no such file)");
  // Checked before opening: a FIFO blocks the open itself, a device such as /dev/zero never ends.
  if (!std::filesystem::is_regular_file(file, ec)) throw ConfigError("", "cannot open '" + file + "': not a regular file");
  const auto bytes = std::filesystem::file_size(file, ec);
  if (ec) throw ConfigError("", "cannot open '" + file + "': " + ec.message());
  if (bytes > static_cast<std::uintmax_t>(max_bytes))
    throw ConfigError("", "'" + file + "' has " + std::to_string(bytes) + " bytes, above the JSON reader's limit of " +
                              std::to_string(max_bytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError("", "cannot open '" + file + "'");
  // At most the limit, should the file have grown since (or been replaced by something that does not end).
  // The buffer is the size found, plus one byte to notice a file that grew (it is not read further).
  std::string text(static_cast<std::size_t>(bytes) + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw ConfigError("", "cannot read '" + file + "'");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > static_cast<std::size_t>(bytes))
    throw ConfigError("", "'" + file + "' grew while it was read (it had " + std::to_string(bytes) +
                              " bytes); read it again once its writer is done");
  return text;
}

json read_json_file_guarded(const std::string& file) { return parse_json_guarded(read_text_file_guarded(file), file); }

json read_table_file_guarded(const std::string& file) {
  std::error_code ec;
  const bool regular = std::filesystem::is_regular_file(file, ec);
  const auto bytes = regular ? std::filesystem::file_size(file, ec) : 0;
  if (regular && !ec)
    check_allocation(static_cast<double>(bytes), kJsonTableBytesPerTextByte,
                     "reading the table '" + file + "' (" + std::to_string(bytes) + " bytes of JSON)");
  const double limit = static_cast<double>(memory_limit_bytes()) / kJsonTableBytesPerTextByte;
  const long max_bytes = static_cast<long>(std::min(limit, 9.0e18));
  return parse_json_guarded(read_text_file_guarded(file, std::max(max_bytes, kJsonMaxBytes)), file);
}

}  // namespace closurelab
