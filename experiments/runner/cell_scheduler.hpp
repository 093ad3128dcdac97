#pragma once
// Where and in which order the cells of a run are computed: `jobs` threads of this process, plus the other ranks
// of an MPI run (rank_group.hpp). Rank 0 hands out the cells, largest expected cost first when several cells run
// at once (ExperimentKind::expected_cost), and receives every finished row; it alone writes (runner.cpp).
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "experiments/runner/rank_group.hpp"

namespace closurelab {

class ExperimentKind;

// One cell to compute, as it travels to a rank: {"experiment", "kind", "index", "total", "id", "label",
// "resolved"} (index is the cell's place in the matrix, 0-based; total the number of cells in the matrix).
using CellTask = json;

// Computes a task: the kind's run (an exception becomes a row with status "error"), then the runner's keys "id",
// "label", "params", "cell_wall_seconds" and "provenance" (`provenance` with this cell's "threads" and the run's
// "ranks" and computing "rank"). Prints "started" and the kind's progress lines to stderr. Never throws for a
// failing cell.
json compute_cell(const CellTask& task, const Registry& registry, json provenance, int threads, const RankGroup& group);

// The order in which to hand out `cells` (indices into `costs`): largest expected cost first (ties in matrix
// order) when `slots` > 1, so that the longest cells do not start last; matrix order for one slot.
std::vector<std::size_t> hand_out_order(const std::vector<std::size_t>& cells, const std::vector<double>& costs,
                                        int slots);

// Rank 0: computes `tasks` in the given order on `jobs` threads here (threads_per_job OpenMP threads each) and
// on the other ranks of `group`, calling `on_row(task, row)` for each finished cell, one call at a time.
// `on_row` returns false to stop handing out cells (a write failed); cells in progress still finish and are
// passed on. Returns when every rank is idle.
void schedule_cells(const std::vector<CellTask>& tasks, int jobs, int threads_per_job, const Registry& registry,
                    const json& provenance, const RankGroup& group,
                    const std::function<bool(const CellTask&, const json&)>& on_row);

// Ranks > 0: computes the cells rank 0 hands out until it says stop (one at a time, with all OpenMP threads).
void work_on_cells(const Registry& registry, const json& provenance, const RankGroup& group);

// One line to stderr, whole, whichever thread writes it.
void log_line(const std::string& line);

}  // namespace closurelab
