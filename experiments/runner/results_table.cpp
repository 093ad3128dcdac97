#include "experiments/runner/results_table.hpp"

#include "core/base/errors.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "experiments/runner/provenance.hpp"

namespace closurelab {

namespace fs = std::filesystem;

fs::path cell_file(const std::string& out_dir, const std::string& id) {
  return fs::path(out_dir) / "cells" / (id + ".json");
}

namespace {

std::string dump_canonical(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

}  // namespace

std::string cell_checksum(const json& row) {
  // Over the row as it reads back from its file (the dump replaces invalid UTF-8), so a write and a read agree.
  json canonical = json::parse(dump_canonical(row));
  canonical.erase(cell_checksum_key);
  return fnv1a64_hex(dump_canonical(canonical));
}

StoredCell read_cell(const fs::path& file, const json& resolved) {
  StoredCell c;
  std::error_code ec;
  if (!fs::exists(file, ec)) return c;
  json row;
  try {
    row = read_json_file(file.string());
  } catch (const std::exception& e) {
    c.state = StoredCell::State::unreadable;
    c.problem = e.what();
    return c;
  }
  if (!row.is_object()) {
    c.state = StoredCell::State::unreadable;
    c.problem = "not a JSON object";
    return c;
  }
  const bool has_checksum = row.contains(cell_checksum_key);
  if (has_checksum) {
    const json stored = row.at(cell_checksum_key);
    if (!stored.is_string() || stored.get<std::string>() != cell_checksum(row)) {
      c.state = StoredCell::State::edited;
      c.problem = "does not match its checksum (edited or corrupt)";
      return c;
    }
    row.erase(cell_checksum_key);
  }
  if (row.value("params", json()) != resolved) {
    c.state = StoredCell::State::other_params;
    c.problem = "computed with other parameters";
    return c;
  }
  c.state = has_checksum ? StoredCell::State::verified : StoredCell::State::legacy;
  c.row = std::move(row);
  return c;
}

void write_row(const fs::path& file, const json& row) {
  json stored = row;
  stored.erase(cell_checksum_key);
  stored[cell_checksum_key] = cell_checksum(stored);
  write_file_atomically(file.string(), stored.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
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
