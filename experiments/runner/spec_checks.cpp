#include "experiments/runner/spec_checks.hpp"

#include <map>

#include "core/base/errors.hpp"
#include "experiments/runner/runner.hpp"

namespace closurelab {

void check_plain_file_name(const std::string& name, const std::string& path) {
  if (name.empty()) throw ConfigError(path, "must not be empty (it names the table file)");
  if (name.size() > 200) throw ConfigError(path, "longer than 200 bytes (it names the table file)");
  if (name.front() == '.') throw ConfigError(path, "'" + name + "' must not start with '.' (a plain file name)");
  for (unsigned char c : name)
    if (c == '/' || c == '\\' || c < 0x20 || c == 0x7f)
      throw ConfigError(path, "'" + name + "' is not a plain file name (no '/', '\\' or control characters)");
}

void check_spec_top_level(const json& spec) {
  if (!spec.is_object()) throw ConfigError("", "an experiment spec must be a JSON object");
  if (!spec.contains("name") || !spec["name"].is_string()) throw ConfigError("/name", "missing string \"name\"");
  check_plain_file_name(spec["name"].get<std::string>(), "/name");
  if (!spec.contains("kind") || !spec["kind"].is_string()) throw ConfigError("/kind", "missing string \"kind\"");
  if (spec.contains("description") && !spec["description"].is_string())
    throw ConfigError("/description", "expected a string, got " + std::string(spec["description"].type_name()));
  if (spec.contains("cells") && spec["cells"].is_array() && spec["cells"].empty())
    throw ConfigError("/cells", "empty: a spec needs at least one cell (leave \"cells\" out to run the base/axes)");
}

void check_distinct_cells(const std::vector<MatrixCell>& cells) {
  std::map<std::string, const MatrixCell*> seen;
  for (const auto& c : cells) {
    const auto [it, fresh] = seen.emplace(c.id, &c);
    if (!fresh)
      throw ConfigError(c.path, "the same cell as " + it->second->path + " (cell id " + c.id +
                                    "): a duplicate would be run twice into one row");
  }
}

}  // namespace closurelab
