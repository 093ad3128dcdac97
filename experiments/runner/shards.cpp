#include "experiments/runner/shards.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numeric>
#include <regex>

#include "core/base/errors.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/out_folder.hpp"
#include "experiments/kinds/provenance.hpp"
#include "experiments/runner/results_table.hpp"
#include "experiments/runner/runner.hpp"

namespace closurelab {

namespace fs = std::filesystem;

namespace {

std::string note_name(int index, int count) { return std::to_string(index) + "-of-" + std::to_string(count) + ".json"; }

}  // namespace

Shard parse_shard(const std::string& text) {
  static const std::regex form("(0|[1-9][0-9]{0,5})/([1-9][0-9]{0,5})");
  std::smatch m;
  if (!std::regex_match(text, m, form))
    throw ConfigError("--shard", "expected i/N with integers 0 <= i < N (e.g. 0/4), got '" + text + "'");
  const Shard s{std::stoi(m[1].str()), std::stoi(m[2].str())};
  if (s.index >= s.count)
    throw ConfigError("--shard", "the shard index must be below the count (0.." + std::to_string(s.count - 1) +
                                     "), got '" + text + "'");
  return s;
}

std::vector<int> assign_shards(const std::vector<double>& costs, int count) {
  std::vector<std::size_t> order(costs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
  std::vector<double> load(static_cast<std::size_t>(count), 0.0);
  std::vector<int> shard(costs.size(), 0);
  for (std::size_t i : order) {
    const auto least = std::min_element(load.begin(), load.end());  // the first of equal loads
    shard[i] = static_cast<int>(least - load.begin());
    *least += costs[i];
  }
  return shard;
}

std::string shard_lock_name(const Shard& shard) {
  return ".closurelab.shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".lock";
}

void write_shard_note(const std::string& dir, const Shard& shard, const json& spec, const std::string& spec_file,
                      const std::vector<std::string>& cell_ids, bool complete) {
  const json note = {{"shard", shard.index},   {"count", shard.count}, {"spec", spec},
                     {"spec_file", spec_file}, {"cells", cell_ids},    {"complete", complete}};
  write_file_atomically((fs::path(dir) / "shards" / note_name(shard.index, shard.count)).string(), note.dump(2) + "\n");
}

int merge_shards(const std::string& dir, const Registry& registry, const std::string& command_line) {
  const fs::path notes_dir = fs::path(dir) / "shards";
  std::vector<json> notes;
  std::error_code ec;
  if (fs::is_directory(notes_dir, ec))
    for (const auto& e : fs::directory_iterator(notes_dir))
      if (e.path().extension() == ".json") notes.push_back(read_json_file(e.path().string()));
  if (notes.empty())
    throw ConfigError("DIR", "no shard notes in '" + notes_dir.string() +
                                 "': merge assembles the table of runs made with --out " + dir + " --shard i/N");
  const json& first = notes.front();
  const int count = first.at("count").get<int>();
  std::vector<bool> noted(static_cast<std::size_t>(count), false), finished(static_cast<std::size_t>(count), false);
  for (const json& n : notes) {
    if (n.at("count") != first.at("count") || n.at("spec") != first.at("spec") ||
        n.at("spec_file") != first.at("spec_file"))
      throw ConfigError("DIR", "the shard notes in '" + notes_dir.string() +
                                   "' come from different runs (other specs or shard counts); keep those of one run");
    const int i = n.at("shard").get<int>();
    if (i < 0 || i >= count)
      throw ConfigError("DIR", "a shard note in '" + notes_dir.string() + "' names shard " + std::to_string(i));
    noted[static_cast<std::size_t>(i)] = true;
    finished[static_cast<std::size_t>(i)] = n.value("complete", false);
  }
  const json& spec = first.at("spec");
  const std::string spec_file = first.at("spec_file").get<std::string>();
  const auto matrix = validate_matrix(spec, registry);
  if (!matrix) return 2;
  const auto& cells = matrix->cells;
  const std::vector<int> shard_of = assign_shards(matrix->costs, count);
  std::vector<json> rows;
  std::vector<std::string> missing;
  std::vector<bool> shard_missing(static_cast<std::size_t>(count), false);
  std::size_t unsealed = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const fs::path file = cell_file(dir, cells[i].id);
    StoredCell stored = read_cell(file, matrix->resolved[i], [&](json p) { return matrix->kind->upgraded_params(std::move(p)); });
    if (stored.usable()) {
      rows.push_back(std::move(*stored.row));
      continue;
    }
    // Merge computes nothing, so a cell it cannot trust is refused like a missing one: an edited row would
    // otherwise enter the table as if computed, and re-running its shard recomputes it.
    const int s = shard_of[i];
    const std::string cell = "cell " + std::to_string(i + 1) + "/" + std::to_string(cells.size()) + " (" +
                             cells[i].label + ") of shard " + std::to_string(s) + "/" + std::to_string(count);
    switch (stored.state) {
      case StoredCell::State::absent: missing.push_back("missing " + cell + ": no " + file.string()); break;
      case StoredCell::State::unreadable:
        missing.push_back("truncated or unreadable: " + file.string() + " (" + cell + ")");
        break;
      default:  // edited, unsealed, other_params
        unsealed += stored.state == StoredCell::State::unsealed;
        missing.push_back(stored.problem + ": " + file.string() + " (" + cell + ")");
    }
    shard_missing[static_cast<std::size_t>(s)] = true;
  }
  if (!missing.empty()) {
    for (const auto& m : missing) std::cerr << "error: " << m << "\n";
    if (unsealed > 0) std::cerr << "error: " << unsealed_cells_hint(dir) << "\n";
    std::cerr << "error: " << missing.size() << " of " << cells.size()
              << " cell(s) missing or unusable; nothing was written. Run" << (unsealed > 0 ? " (or seal)" : "")
              << ":\n";
    for (int s = 0; s < count; ++s)
      if (shard_missing[static_cast<std::size_t>(s)])
        std::cerr << "  closurelab run " << spec_file << " --out " << dir << " --shard " << s << "/" << count << "   ("
                  << (!noted[static_cast<std::size_t>(s)]     ? "never run"
                      : finished[static_cast<std::size_t>(s)] ? "finished"
                                                              : "did not finish")
                  << ")\n";
    return 2;
  }
  std::unique_ptr<FolderLock> lock;
  try {
    lock = std::make_unique<FolderLock>(dir, command_line);
  } catch (const FolderBusy& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  const fs::path table_file = fs::path(dir) / (spec.at("name").get<std::string>() + ".json");
  std::size_t failed = 0;
  for (const auto& r : rows) failed += r.value("status", "") == "error";
  try {
    const bool written = write_table(table_file, make_table(spec, spec_file, rows, true), false);
    std::cerr << "[" << spec.at("name").get<std::string>() << "] " << (written ? "wrote " : "kept ")
              << table_file.string() << " (" << cells.size() << " cells from " << count << " shard(s), " << failed
              << " failed)\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\nerror: the table was not written\n";
    return 1;
  }
  return failed == 0 ? 0 : 1;
}

}  // namespace closurelab
