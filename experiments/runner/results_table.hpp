#pragma once
// The files of a run's output folder: one row per finished cell (DIR/cells/<id>.json) and the table
// DIR/<name>.json. A run and `closurelab merge` write the table with the same function, so a merged table is the
// one a single run would have written.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {

// DIR/cells/<id>.json
std::filesystem::path cell_file(const std::string& out_dir, const std::string& id);

// The row in `file` if it is there, readable and was computed with exactly these resolved parameters
// (whatever its status); nothing otherwise.
std::optional<json> stored_row(const std::filesystem::path& file, const json& resolved);

// Writes a finished cell's row atomically.
void write_row(const std::filesystem::path& file, const json& row);

// The table of `rows` (in the matrix's order): the spec, the table's provenance derived from the rows
// (provenance.hpp), `complete`, the rows. Nothing of "now" enters it.
json make_table(const json& spec, const std::string& spec_file, const std::vector<json>& rows, bool complete);

// Writes `table` to `file` atomically; if `computed_any` is false and `file` already holds a complete table with
// the same spec and rows, leaves it as it is (a re-run that computed nothing changes no file). Returns whether
// it wrote.
bool write_table(const std::filesystem::path& file, const json& table, bool computed_any);

}  // namespace closurelab
