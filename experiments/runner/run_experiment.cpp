// `closurelab run`: rank 0 checks the folder, validates the matrix, takes the lock, hands out the cells
// (cell_scheduler.hpp) and writes each finished row at once, then the table (results_table.hpp) or, for a shard,
// its note (shards.hpp); the other ranks of an MPI run compute what they are handed.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "core/base/errors.hpp"
#include "core/base/run_progress.hpp"
#include "core/base/timing_noise.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/cell_scheduler.hpp"
#include "experiments/runner/out_folder.hpp"
#include "experiments/kinds/provenance.hpp"
#include "experiments/runner/rank_group.hpp"
#include "experiments/runner/results_table.hpp"
#include "experiments/runner/runner.hpp"

namespace closurelab {

namespace {

std::string format_seconds(double s) { return format_duration(s); }  // core/base/run_progress.hpp

// Rank 0's part of a run, from the folder check to the table; the other ranks are served (and finally released)
// by schedule_cells. Every early return releases them with an empty schedule first.
int run_as_rank0(const json& spec, const Registry& registry, const RunOptions& options, const RankGroup& group) {
  namespace fs = std::filesystem;
  const json provenance_here = provenance(options.command_line);
  auto give_up = [&](int code) {
    schedule_cells({}, 0, 1, registry, provenance_here, group, [](const CellTask&, const json&) { return true; });
    return code;
  };
  try {
    check_output_folder(options.out_dir);  // before anything is validated or computed; writes nothing
    if (options.jobs > 1 && group.size() > 1)
      throw ConfigError("--jobs",
                        "with mpirun each rank computes one cell at a time: give more ranks instead of --jobs " +
                            std::to_string(options.jobs));
  } catch (const ConfigError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return give_up(2);
  }
  const auto matrix = validate_matrix(spec, registry);  // every cell, before any runs
  if (!matrix) return give_up(2);
  const auto& cells = matrix->cells;
  const std::string name = spec["name"].get<std::string>();
  const Shard& shard = options.shard;
  std::unique_ptr<FolderLock> lock, shard_lock;  // one lock per folder (out_folder.hpp): a shard holds it shared
  try {
    lock = std::make_unique<FolderLock>(options.out_dir, options.command_line, ".closurelab.lock",
                                        shard.active() ? LockMode::shared : LockMode::exclusive);
    if (shard.active())
      shard_lock = std::make_unique<FolderLock>(options.out_dir, options.command_line, shard_lock_name(shard));
  } catch (const FolderBusy& e) {
    std::cerr << "error: " << e.what() << "\n";
    return give_up(2);
  } catch (const std::exception& e) {
    std::cerr << "error: cannot use the output folder: " << e.what() << "\n";
    return give_up(2);
  }
  // This run's cells (a shard's share, or all), the finished ones taken from DIR/cells.
  const std::string tag = "[" + name + "] ";
  const std::vector<int> shard_of =
      shard.active() ? assign_shards(matrix->costs, shard.count) : std::vector<int>(cells.size(), 0);
  std::vector<std::size_t> mine, to_compute;
  std::vector<std::string> mine_ids;
  std::vector<json> rows(cells.size());
  std::vector<bool> done(cells.size(), false);
  std::size_t computed = 0, finished = 0, cached = 0, unsealed = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (shard_of[i] != shard.index) continue;
    mine.push_back(i);
    mine_ids.push_back(cells[i].id);
    const fs::path file = cell_file(options.out_dir, cells[i].id);
    StoredCell stored = options.force ? StoredCell{} : read_cell(file, matrix->resolved[i], [&](json p) { return matrix->kind->upgraded_params(std::move(p)); });
    // A damaged, edited or unsealed file is never taken as this cell's result, and never replaced without a word.
    using State = StoredCell::State;
    if (stored.state == State::unreadable || stored.state == State::edited || stored.state == State::unsealed) {
      unsealed += stored.state == State::unsealed;
      std::cerr << tag << "cell " << (i + 1) << "/" << cells.size() << " (" << cells[i].label << "): "
                << (stored.state == State::unreadable ? "truncated or unreadable: " + file.string()
                                                      : file.string() + " " + stored.problem)
                << "; recomputing it\n";
    }
    if (stored.usable() && stored.row->value("status", "") != "error") {
      rows[i] = std::move(*stored.row);
      done[i] = true;
      ++cached;
      ++finished;
      std::cerr << tag << "cell " << (i + 1) << "/" << cells.size() << " (" << cells[i].label
                << ") already done; skipped (use --force to re-run)\n";
    } else {
      to_compute.push_back(i);
    }
  }
  if (unsealed > 0)
    std::cerr << tag << "note: " << unsealed << " cell file(s) without a checksum are recomputed: "
              << unsealed_cells_hint(options.out_dir) << "\n";
  const fs::path table_file = fs::path(options.out_dir) / (name + ".json");
  auto finished_rows = [&]() {
    std::vector<json> v;
    for (std::size_t i : mine)
      if (done[i]) v.push_back(rows[i]);
    return v;
  };
  try {
    if (shard.active()) write_shard_note(options.out_dir, shard, spec, options.spec_file, mine_ids, false);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return give_up(1);
  }

  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(to_compute.size())));
  const int threads_per_job = std::max(1, omp_get_max_threads() / jobs);
  const int slots = jobs * group.size();
  std::vector<CellTask> tasks;
  for (std::size_t i : hand_out_order(to_compute, matrix->costs, slots))
    tasks.push_back({{"experiment", name},
                     {"kind", matrix->kind->name()},
                     {"index", i},
                     {"total", cells.size()},
                     {"id", cells[i].id},
                     {"label", cells[i].label},
                     {"resolved", matrix->resolved[i]}});
  double computed_seconds = 0.0, first_seconds = 0.0;  // the first computed cell may carry shared work
  std::string write_error;
  const auto run_start = std::chrono::steady_clock::now();
  auto run_clock = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count(); };
  PartialTableSchedule table_schedule;
  schedule_cells(
      tasks, jobs, threads_per_job, registry, provenance_here, group, [&](const CellTask& t, const json& row) {
        const std::size_t i = t.at("index").get<std::size_t>();
        const double secs = row.at("cell_wall_seconds").get<double>();
        try {
          write_row(cell_file(options.out_dir, cells[i].id), row);  // at once: a killed run resumes from here
          rows[i] = row;
          done[i] = true;
          if (computed++ == 0)
            first_seconds = secs;
          else
            computed_seconds += secs;
          ++finished;
          // The partial table, rewritten only as often as PartialTableSchedule allows (linear in the cells); the
          // final table is written below.
          if (!shard.active() && table_schedule.due(run_clock())) {
            const double w0 = run_clock();
            write_table(table_file, make_table(spec, options.spec_file, finished_rows(), false, options.overrides), true);
            table_schedule.written(w0, run_clock());
          }
        } catch (const std::exception& e) {
          write_error = e.what();
          return false;
        }
        // One line per cell with an estimate of the time left (from the cells computed so far): the mean of the
        // computed cells times the cells left over the cells computed at once; the first computed cell is left out of
        // the mean once there are others (it may have done work the others reuse, e.g. a direct SPH reference).
        const std::size_t left = mine.size() - finished;
        std::string line = tag + "cell " + std::to_string(i + 1) + "/" + std::to_string(cells.size()) + " (" +
                           cells[i].label + ") " + row.value("status", "?") + " in " + format_seconds(secs) + "; " +
                           std::to_string(finished) + "/" + std::to_string(mine.size()) + " done";
        const double mean = computed > 1 ? computed_seconds / static_cast<double>(computed - 1) : first_seconds;
        if (left > 0) line += ", about " + format_seconds(mean * static_cast<double>(left) / slots) + " left";
        if (row.contains("error") && row["error"].is_string()) line += ": " + row["error"].get<std::string>();
        line += noisy_timing_note(row);
        log_line(line);
        return true;
      });
  if (!write_error.empty()) {
    std::cerr << "error: " << write_error << "\nerror: the run stopped; " << computed
              << " cell(s) computed in this run are kept in " << (fs::path(options.out_dir) / "cells").string() << "\n";
    return 1;
  }
  std::size_t failed = 0, not_ok = 0;
  for (std::size_t i : mine) {
    const std::string status = rows[i].value("status", "");
    failed += status == "error";
    not_ok += status != "error" && status != "ok";
  }
  const std::string counts = std::to_string(mine.size()) + " cells: " + std::to_string(computed) + " computed, " +
                             std::to_string(cached) + " cached, " + std::to_string(failed) + " failed" +
                             (not_ok > 0 ? ", " + std::to_string(not_ok) + " not ok (numerical_issue or no_convergence)" : "");
  try {
    if (shard.active()) {
      write_shard_note(options.out_dir, shard, spec, options.spec_file, mine_ids, true);
      std::cerr << tag << "shard " << shard.text() << " done (" << counts
                << "); when every shard is done: closurelab merge " << options.out_dir << "\n";
    } else {
      const bool written =
          write_table(table_file, make_table(spec, options.spec_file, finished_rows(), true, options.overrides), computed > 0);
      if (!written) std::cerr << tag << "nothing computed; " << table_file.string() << " left as it is\n";
      std::cerr << tag << (written ? "wrote " : "kept ") << table_file.string() << " (" << counts << ")\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\nerror: the " << (shard.active() ? "shard note" : "table")
              << " was not written; the cells are kept in " << (fs::path(options.out_dir) / "cells").string() << "\n";
    return 1;
  }
  if (failed > 0) return 1;
  if (options.strict && not_ok > 0) {
    std::cerr << tag << "--strict: " << not_ok << " row(s) not ok; exit 3\n";
    return 3;
  }
  return 0;
}

}  // namespace

int run_experiment(const json& spec, const Registry& registry, const RunOptions& options) {
  const RankGroup group;  // MPI_Init under mpirun; MPI_Finalize when the run is over
  if (group.rank() == 0) {
    try {
      const int code = run_as_rank0(spec, registry, options, group);
      if (options.after_run_on_rank0) options.after_run_on_rank0();
      return code;
    } catch (const std::exception& e) {
      // Unexpected: the other ranks may still wait for cells; end them rather than hang in MPI_Finalize.
      if (group.size() > 1) {
        std::cerr << "error: " << e.what() << "\n";
        group.abort(1);
      }
      throw;
    }
  }
  work_on_cells(registry, provenance(options.command_line), group);
  return 0;
}

}  // namespace closurelab
