#pragma once
// The experiment runner (DESIGN.md §3): expands an experiment matrix (base + cartesian axes + explicit
// cells), validates every cell before running any, runs them (resuming finished cells), and writes one
// JSON row per cell (DIR/cells/<id>.json) and the table DIR/<name>.json with provenance. The cells run on
// threads of this process and, under mpirun, on the other ranks (cell_scheduler.hpp); a shard of the matrix
// runs alone and `closurelab merge` writes the table (shards.hpp).
#include <optional>
#include <functional>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "experiments/runner/shards.hpp"

namespace closurelab {

struct MatrixCell {
  std::string id;     // stable hash of the cell's JSON
  std::string label;  // axis values, human readable
  std::string path;   // JSON path in the spec, for error messages
  json config;        // base merged with the axis values / explicit cell
};

// Expands the spec; throws ConfigError naming the JSON path on a malformed spec.
std::vector<MatrixCell> expand_matrix(const json& spec);

// Sets `value` at a dotted path ("scene.n_y") inside `target`, creating objects on the way. An object value
// merges into an object already there (deep merge: {"solver": {"scheme": "staggered"}} keeps the base's other
// solver keys), unless it names another strategy ({"name": ...} different from the one there), which replaces it.
void set_dotted(json& target, const std::string& dotted, const json& value, const std::string& path);

// `closurelab run --set KEY=VALUE`: sets the dotted KEY in the base, in every axis value and every cell that
// gives KEY or an object above it (an axis over KEY itself keeps the one value), so that VALUE holds in every
// cell; VALUE is parsed as JSON, else taken as a string. ConfigError when an axis or cell varies a key inside KEY
// (it would override part of VALUE) or KEY=VALUE is malformed. Returns what it replaced that the spec varied, one
// sentence each (an axis over KEY collapsed to VALUE, an axis value's or a cell's own different value of KEY), for
// the run to say (a note on stderr, dry run included) and to record (the table's `overrides`).
std::vector<std::string> apply_override(json& spec, const std::string& assignment);

class ExperimentKind;

// A matrix whose every cell is valid: the cells, their kind, each cell resolved (defaults filled in) and its
// expected cost (ExperimentKind::expected_cost).
struct ValidMatrix {
  std::vector<MatrixCell> cells;
  const ExperimentKind* kind = nullptr;
  std::vector<json> resolved;
  std::vector<double> costs;
};

// Expands and validates every cell; prints each problem (with its JSON path and cell) to stderr and returns
// nothing if there is any.
std::optional<ValidMatrix> validate_matrix(const json& spec, const Registry& registry);

struct RunOptions {
  std::string out_dir = "out/runs/unnamed";  // `closurelab run` without --out: out/runs/<spec name> (git-ignored)
  int jobs = 1;
  bool force = false;  // re-run finished cells
  std::string command_line;
  std::string spec_file;
  Shard shard;  // --shard i/N; not sharded by default
  // --strict: a row whose status is not "ok" (numerical_issue, no_convergence: recorded, not trustworthy) makes the
  // exit code 3 once everything is written.
  bool strict = false;
  // The --set assignments and what each replaced that the spec varied ([{"set": "KEY=VALUE", "replaced":
  // [...]}], apply_override), recorded in the table as `overrides`; empty: no --set.
  json overrides = json::array();
  // Called on rank 0 only, when its run is over (e.g. the store summary: under mpirun once, not once per rank).
  std::function<void()> after_run_on_rank0;
};

// Runs the whole matrix (or one shard); returns the process exit code (0: all cells ok or recorded, 1: a cell
// failed or a write failed, 2: invalid spec or options, or the folder is in use, 3: with `strict`, a row not ok). Under mpirun every rank calls
// it: rank 0 validates, hands out the cells and writes; the other ranks compute what they are handed.
int run_experiment(const json& spec, const Registry& registry, const RunOptions& options);

}  // namespace closurelab
