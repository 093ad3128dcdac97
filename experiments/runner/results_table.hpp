#pragma once
// The files of a run's output folder: one row per finished cell (DIR/cells/<id>.json) and the table
// DIR/<name>.json. A run and `closurelab merge` write the table with the same function, so a merged table is the
// one a single run would have written.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {

// DIR/cells/<id>.json
std::filesystem::path cell_file(const std::string& out_dir, const std::string& id);

// A cell file holds the row and `cell_fnv1a64`: 16 hex digits of the FNV-1a (reference_store.hpp) of the row's
// canonical dump without that key, so a file edited by hand or damaged is never reused or merged as if computed.
// A file without the key (written before cells carried it, or edited with the key deleted) is `unsealed` and
// treated as an edited one; `closurelab seal DIR` (seal_cell_file) adds the key to a folder of trusted old cells.
inline constexpr const char* cell_checksum_key = "cell_fnv1a64";

struct StoredCell {
  enum class State {
    absent,        // no file
    unreadable,    // truncated or not a JSON object (`problem` says why)
    edited,        // its checksum does not match its contents
    unsealed,      // no checksum (an older closurelab, or a hand edit that deleted it): not used
    other_params,  // intact, but computed with other resolved parameters (an older default)
    verified       // checksum matches
  };
  State state = State::absent;
  std::optional<json> row;  // verified only: the row, without the checksum
  std::string problem;
  bool usable() const { return row.has_value(); }
};

// What `file` holds for a cell with these resolved parameters (whatever the row's status). The row's stored
// parameters are compared after `upgrade` (the kind's ExperimentKind::upgraded_params: an earlier name of a renamed
// parameter mapped to today's), the row itself kept as it was computed.
StoredCell read_cell(const std::filesystem::path& file, const json& resolved,
                     const std::function<json(json)>& upgrade = {});

// The checksum a cell file carries for `row` (without cell_checksum_key).
std::string cell_checksum(const json& row);

// Writes a finished cell's row atomically, with its checksum.
void write_row(const std::filesystem::path& file, const json& row);

// What to do with unsealed cell files that are trusted (the line a run and `merge` print after naming them).
std::string unsealed_cells_hint(const std::string& out_dir);

// Sealing one cell file (`closurelab seal DIR`, seal_command.hpp): a file without `cell_fnv1a64` gets it, written
// as write_row writes a row; the row itself is unchanged (checked: the sealed file reads back as the same row).
struct SealOutcome {
  enum class Result {
    sealed,          // the key added (or, with write = false, it would be)
    already_sealed,  // it has the key and the key matches
    refused          // left as it is: `problem` says why (unreadable, not a cell's row, a checksum that does not
                     // match, a row that would not read back unchanged)
  };
  Result result = Result::refused;
  // sealed: the file's bytes were not closurelab's own dump of its row (other indentation, key order or number
  // spelling), so more than the one key's line changes; the row still reads back the same.
  bool formatting_changed = false;
  std::string problem;
};
SealOutcome seal_cell_file(const std::filesystem::path& file, bool write);

// The table of `rows` (in the matrix's order): the spec, the table's provenance derived from the rows
// (provenance.hpp), `complete`, the rows, and `overrides` (the run's --set assignments with what each replaced,
// RunOptions::overrides) when there were any. Nothing of "now" enters it.
json make_table(const json& spec, const std::string& spec_file, const std::vector<json>& rows, bool complete,
               const json& overrides = json::array());

// When a run rewrites its partial table ("complete": false) between cells. The cells on disk are what a resumed
// run reads; the partial table is a convenience for a reader during the run. Rewriting it after every cell made
// a run quadratic in its cells (each write holds every finished row: 1000 trivial cells took 197 s for 32 s of
// cells), so a rewrite is due only once at least `min_interval` seconds and `cost_ratio` times the last rewrite's
// duration have passed since it ended: the time spent rewriting stays below 1/cost_ratio of the run's. The first
// finished cell is always written at once, so a table that cannot be written stops the run after one cell.
class PartialTableSchedule {
 public:
  explicit PartialTableSchedule(double min_interval = 1.0, double cost_ratio = 20.0)
      : min_interval_(min_interval), cost_ratio_(cost_ratio) {}
  // `now`: seconds on the run's clock.
  bool due(double now) const {
    const double since = now - last_end_;
    return !any_ || (since >= min_interval_ && since >= cost_ratio_ * last_cost_);
  }
  // A rewrite ran from `start` to `end` (the run's clock).
  void written(double start, double end) {
    any_ = true;
    last_end_ = end;
    last_cost_ = end - start;
  }

 private:
  double min_interval_, cost_ratio_, last_end_ = 0.0, last_cost_ = 0.0;
  bool any_ = false;
};

// Writes `table` to `file` atomically; if `computed_any` is false and `file` already holds a complete table with
// the same spec and rows, leaves it as it is (a re-run that computed nothing changes no file). Returns whether
// it wrote.
bool write_table(const std::filesystem::path& file, const json& table, bool computed_any);

}  // namespace closurelab
