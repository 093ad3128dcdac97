#include "experiments/runner/results_table.hpp"

#include <fstream>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/json_reader.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

namespace fs = std::filesystem;

fs::path cell_file(const std::string& out_dir, const std::string& id) {
  return fs::path(out_dir) / "cells" / (id + ".json");
}

namespace {

std::string dump_canonical(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// A file's text as closurelab writes it: indented by two, sorted keys, a final newline.
std::string dump_file(const json& j) { return j.dump(2, ' ', false, json::error_handler_t::replace) + "\n"; }

// The text of a cell file holding `row` (without the checksum) and its checksum.
std::string sealed_text(const json& row) {
  json stored = row;
  stored.erase(cell_checksum_key);
  stored[cell_checksum_key] = cell_checksum(stored);
  return dump_file(stored);
}

// Through the guarded reader: a FIFO named *.json in cells/ blocked seal, a link to /dev/zero grew without end.
std::string read_text_file(const fs::path& file) { return read_text_file_guarded(file.string()); }

SealOutcome refused(const std::string& problem) { return {SealOutcome::Result::refused, false, problem}; }

}  // namespace

std::string cell_checksum(const json& row) {
  // Over the row as it reads back from its file (the dump replaces invalid UTF-8), so a write and a read agree.
  json canonical = json::parse(dump_canonical(row));
  canonical.erase(cell_checksum_key);
  return fnv1a64_hex(dump_canonical(canonical));
}

StoredCell read_cell(const fs::path& file, const json& resolved, const std::function<json(json)>& upgrade) {
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
  // Without the key the file cannot be told from a hand edit that deleted it: not used (seal trusted old files).
  if (!row.contains(cell_checksum_key)) {
    c.state = StoredCell::State::unsealed;
    c.problem = "carries no checksum (" + std::string(cell_checksum_key) +
                ": written before cells were sealed, or edited with the key deleted)";
    return c;
  }
  const json stored = row.at(cell_checksum_key);
  if (!stored.is_string() || stored.get<std::string>() != cell_checksum(row)) {
    c.state = StoredCell::State::edited;
    c.problem = "does not match its checksum (edited or corrupt)";
    return c;
  }
  row.erase(cell_checksum_key);
  const json params = row.value("params", json());
  if ((upgrade ? upgrade(params) : params) != resolved) {
    c.state = StoredCell::State::other_params;
    c.problem = "computed with other parameters";
    return c;
  }
  c.state = StoredCell::State::verified;
  c.row = std::move(row);
  return c;
}

void write_row(const fs::path& file, const json& row) { write_file_atomically(file.string(), sealed_text(row)); }

std::string unsealed_cells_hint(const std::string& out_dir) {
  return "a cell file without " + std::string(cell_checksum_key) +
         " is not trusted; if these files are trusted cells of an older closurelab, seal the folder first: "
         "closurelab seal " + out_dir;
}

SealOutcome seal_cell_file(const fs::path& file, bool write) {
  std::string text;
  json row;
  try {
    text = read_text_file(file);
    row = read_json_file(file.string());
  } catch (const std::exception& e) {
    return refused(std::string("truncated or unreadable (") + e.what() + ")");
  }
  if (!row.is_object()) return refused("not a JSON object");
  if (row.contains(cell_checksum_key)) {
    const json& stored = row.at(cell_checksum_key);
    if (stored.is_string() && stored.get<std::string>() == cell_checksum(row))
      return {SealOutcome::Result::already_sealed, false, ""};
    return refused("does not match its checksum (edited or corrupt)");
  }
  if (!row.contains("params")) return refused("holds no \"params\": not a cell's row");
  if (row.value("id", json()) != file.stem().string()) return refused("its row's \"id\" is not its file's name");
  const std::string sealed = sealed_text(row);
  json back = json::parse(sealed);
  back.erase(cell_checksum_key);
  if (back != row) return refused("its row would not read back unchanged (invalid UTF-8?)");
  SealOutcome out{SealOutcome::Result::sealed, text != dump_file(row), ""};
  if (write) write_file_atomically(file.string(), sealed);
  return out;
}

json make_table(const json& spec, const std::string& spec_file, const std::vector<json>& rows, bool complete,
               const json& overrides) {
  json table = {{"experiment", spec.at("name")},
          {"kind", spec.at("kind")},
          {"description", spec.value("description", "")},
          {"spec_file", spec_file},
          {"spec", spec},
          {"provenance", table_provenance(rows)},
          {"complete", complete},
          {"rows", rows}};
  if (overrides.is_array() && !overrides.empty()) table["overrides"] = overrides;
  return table;
}

bool write_table(const fs::path& file, const json& table, bool computed_any) {
  if (!computed_any) {
    try {
      if (fs::exists(file)) {
        const json old = read_table_file_guarded(file.string());
        if (old.value("complete", false) && table.value("complete", false) &&
            old.value("spec", json()) == table.at("spec") && old.value("rows", json()) == table.at("rows"))
          return false;
      }
    } catch (const std::exception&) {
      // An unreadable old table is replaced.
    }
  }
  write_file_atomically(file.string(), dump_file(table));
  return true;
}

}  // namespace closurelab
