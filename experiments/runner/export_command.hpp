#pragma once
// `closurelab export TABLE.json [--csv] [--long] [--out FILE]`: a results table as CSV for other tools (pandas, a
// spreadsheet), one record per row: id, label, status, then every leaf of the row's params, errors and cost
// as a dotted column name (arrays of numbers, e.g. profiles, are left out: they are not table cells); with --long,
// the rows' profiles and fields, one record per coarse node.
#include <string>

#include "core/base/params.hpp"
#include "experiments/runner/command_options.hpp"

namespace closurelab {

// The CSV text of a table (`table`: the runner's JSON table). Columns are the union over the rows, in sorted
// order after the three leading ones; a row without a column has an empty cell.
std::string table_to_csv(const json& table);

// The long CSV of a table's coarse data: columns id, label, i, j, x, y, then the union over the rows of their
// per-node values (a 2D row's fields as <field>_vx, <field>_vy, outside_solid, ...; a column row's profile lists,
// with i and x empty), one record per node, j slowest; a row without fields or profile has no record, a row without
// a column leaves it empty.
std::string table_to_long_csv(const json& table);

// Its options (command_options.hpp).
const CommandSpec& export_command_spec();
int run_export_command(int argc, char** argv);

}  // namespace closurelab
