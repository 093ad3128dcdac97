#pragma once
// The experiment runner (DESIGN.md §3): expands an experiment matrix (base + cartesian axes + explicit
// cells), validates every cell before running any, runs them (resuming finished cells), and writes one
// JSON row per cell (DIR/cells/<id>.json) and the table DIR/<name>.json with provenance.
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"

namespace closurelab {

struct MatrixCell {
  std::string id;     // stable hash of the cell's JSON
  std::string label;  // axis values, human readable
  std::string path;   // JSON path in the spec, for error messages
  json config;        // base merged with the axis values / explicit cell
};

// Expands the spec; throws ConfigError naming the JSON path on a malformed spec.
std::vector<MatrixCell> expand_matrix(const json& spec);

// Sets `value` at a dotted path ("scene.n_y") inside `target`, creating objects on the way.
void set_dotted(json& target, const std::string& dotted, const json& value, const std::string& path);

struct RunOptions {
  std::string out_dir = "results";
  int jobs = 1;
  bool force = false;  // re-run finished cells
  std::string command_line;
  std::string spec_file;
};

// Runs the whole matrix; returns the process exit code (0: all cells ok or recorded, 2: invalid spec).
int run_experiment(const json& spec, const Registry& registry, const RunOptions& options);

}  // namespace closurelab
