#pragma once
// Checks of an experiment spec that the matrix expansion needs before it copies anything: the top-level keys'
// types (a non-string "description" used to pass validation and abort the run after its first cell), the name
// as a plain file name (it becomes DIR/<name>.json), a non-empty cell list, and distinct cells.
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {

struct MatrixCell;

// Throws ConfigError naming the JSON path ("/name", "/description", "/cells", ...).
void check_spec_top_level(const json& spec);

// Two cells with the same configuration would share one id and one row: an error naming both paths.
void check_distinct_cells(const std::vector<MatrixCell>& cells);

// A plain file name: non-empty, at most 200 bytes, no '/', no NUL or control character, not starting with '.'.
void check_plain_file_name(const std::string& name, const std::string& path);

}  // namespace closurelab
