#include "experiments/runner/results_table.hpp"

#include "core/base/errors.hpp"
#include "experiments/runner/provenance.hpp"

namespace closurelab {

namespace fs = std::filesystem;

fs::path cell_file(const std::string& out_dir, const std::string& id) {
  return fs::path(out_dir) / "cells" / (id + ".json");
}

std::optional<json> stored_row(const fs::path& file, const json& resolved) {
  try {
    if (!fs::exists(file)) return std::nullopt;
    json row = read_json_file(file.string());
    if (row.is_object() && row.value("params", json()) == resolved) return row;
  } catch (const std::exception&) {
    // An unreadable previous result counts as absent (it is simply re-run).
  }
  return std::nullopt;
}

void write_row(const fs::path& file, const json& row) {
  write_file_atomically(file.string(), row.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
}

json make_table(const json& spec, const std::string& spec_file, const std::vector<json>& rows, bool complete) {
  return {{"experiment", spec.at("name")},
          {"kind", spec.at("kind")},
          {"description", spec.value("description", "")},
          {"spec_file", spec_file},
          {"spec", spec},
          {"provenance", table_provenance(rows)},
          {"complete", complete},
          {"rows", rows}};
}

bool write_table(const fs::path& file, const json& table, bool computed_any) {
  if (!computed_any) {
    try {
      if (fs::exists(file)) {
        const json old = read_json_file(file.string());
        if (old.value("complete", false) && table.value("complete", false) &&
            old.value("spec", json()) == table.at("spec") && old.value("rows", json()) == table.at("rows"))
          return false;
      }
    } catch (const std::exception&) {
      // An unreadable old table is replaced.
    }
  }
  write_file_atomically(file.string(), table.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
  return true;
}

}  // namespace closurelab
