#include "experiments/runner/runner.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/base/errors.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/out_folder.hpp"
#include "experiments/runner/provenance.hpp"
#include "experiments/runner/spec_checks.hpp"

namespace closurelab {

namespace {

std::string fnv1a_hex(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return std::string(buf, 12);
}

void merge_into(json& target, const json& patch) {
  for (const auto& [k, v] : patch.items()) {
    if (v.is_object() && target.contains(k) && target[k].is_object()) {
      merge_into(target[k], v);
    } else {
      target[k] = v;
    }
  }
}

std::string value_label(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

}  // namespace

void set_dotted(json& target, const std::string& dotted, const json& value, const std::string& path) {
  json* node = &target;
  std::stringstream ss(dotted);
  std::string part, next;
  std::getline(ss, part, '.');
  while (std::getline(ss, next, '.')) {
    if (part.empty()) throw ConfigError(path, "empty component in dotted key '" + dotted + "'");
    if (!node->contains(part)) (*node)[part] = json::object();
    node = &(*node)[part];
    if (!node->is_object()) throw ConfigError(path, "'" + part + "' in '" + dotted + "' is not an object");
    part = next;
  }
  (*node)[part] = value;
}

std::vector<MatrixCell> expand_matrix(const json& spec) {
  if (!spec.is_object()) throw ConfigError("", "an experiment spec must be a JSON object");
  for (const auto& [k, v] : spec.items()) {
    static const std::vector<std::string> allowed = {"name", "kind", "description", "base", "axes", "cells"};
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      throw ConfigError("/" + k, "unknown key; allowed keys: name, kind, description, base, axes, cells");
  }
  check_spec_top_level(spec);
  const json base = spec.value("base", json::object());
  if (!base.is_object()) throw ConfigError("/base", "expected an object");

  // Cartesian product of the axes (keys in sorted order, values in the listed order).
  std::vector<std::pair<json, std::string>> combos = {{base, ""}};
  if (spec.contains("axes")) {
    const json& axes = spec["axes"];
    if (!axes.is_object()) throw ConfigError("/axes", "expected an object of dotted keys to value lists");
    for (const auto& [key, values] : axes.items()) {
      const std::string at = "/axes/" + key;
      if (!values.is_array() || values.empty()) throw ConfigError(at, "expected a non-empty array of values");
      std::vector<std::pair<json, std::string>> next;
      for (const auto& [cfg, label] : combos) {
        for (const auto& v : values) {
          json c = cfg;
          set_dotted(c, key, v, at);
          next.emplace_back(c, label + (label.empty() ? "" : ", ") + key + "=" + value_label(v));
        }
      }
      combos = std::move(next);
    }
  }
  std::vector<MatrixCell> cells;
  const bool has_axes = spec.contains("axes");
  if (spec.contains("cells")) {
    const json& list = spec["cells"];
    if (!list.is_array()) throw ConfigError("/cells", "expected an array of cell objects");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = "/cells/" + std::to_string(i);
      if (!list[i].is_object()) throw ConfigError(at, "expected an object");
      for (const auto& [cfg, label] : (has_axes ? combos : std::vector<std::pair<json, std::string>>{{base, ""}})) {
        json c = cfg;
        std::string cell_label = label;
        for (const auto& [k, v] : list[i].items()) {
          if (k == "label") {
            if (!v.is_string()) throw ConfigError(at + "/label", "expected a string");
            cell_label = v.get<std::string>() + (label.empty() ? "" : ", " + label);
            continue;
          }
          set_dotted(c, k, v, at + "/" + k);
        }
        cells.push_back({"", cell_label, at, c});
      }
    }
  } else {
    for (std::size_t i = 0; i < combos.size(); ++i)
      cells.push_back({"", combos[i].second, has_axes ? "/axes[" + std::to_string(i) + "]" : "/base", combos[i].first});
  }
  for (auto& c : cells) {
    c.id = fnv1a_hex(spec["kind"].get<std::string>() + c.config.dump());
    if (c.label.empty()) c.label = c.id;
  }
  check_distinct_cells(cells);
  return cells;
}

namespace {

// Whether `file` holds a complete table with exactly these rows and this spec (then a run that computed
// nothing leaves it alone, whatever its header says).
bool table_unchanged(const std::filesystem::path& file, const json& spec, const std::vector<json>& rows) {
  try {
    if (!std::filesystem::exists(file)) return false;
    const json old = read_json_file(file.string());
    return old.value("complete", false) && old.value("spec", json()) == spec && old.value("rows", json()) == json(rows);
  } catch (const std::exception&) {
    return false;
  }
}

std::string format_seconds(double s) {
  char buf[32];
  if (s < 90) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 5400) std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

}  // namespace

int run_experiment(const json& spec, const Registry& registry, const RunOptions& options) {
  namespace fs = std::filesystem;
  std::vector<MatrixCell> cells;
  const ExperimentKind* kind = nullptr;
  std::vector<json> resolved;
  std::vector<std::string> problems;
  try {
    check_output_folder(options.out_dir);  // before anything is validated or computed; writes nothing
  } catch (const ConfigError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  try {
    cells = expand_matrix(spec);
    kind = &find_experiment_kind(spec["kind"].get<std::string>(), "/kind");
  } catch (const ConfigError& e) {
    std::cerr << "error: invalid experiment spec: " << e.what() << "\n";
    return 2;
  }
  // Validate every cell before running any.
  for (const auto& c : cells) {
    try {
      resolved.push_back(kind->resolve(c.config, c.path, registry));
    } catch (const ConfigError& e) {
      problems.push_back(std::string(e.what()) + "  [cell " + c.label + "]");
    }
  }
  if (!problems.empty()) {
    for (const auto& p : problems) std::cerr << "error: " << p << "\n";
    std::cerr << "error: " << problems.size() << " invalid cell(s); nothing was run\n";
    return 2;
  }
  const std::string name = spec["name"].get<std::string>();
  const fs::path out(options.out_dir);
  std::unique_ptr<FolderLock> lock;
  try {
    lock = std::make_unique<FolderLock>(options.out_dir, options.command_line);
  } catch (const FolderBusy& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: cannot use the output folder: " << e.what() << "\n";
    return 2;
  }
  const json prov = provenance(options.command_line);
  const fs::path table_file = out / (name + ".json");
  std::vector<json> rows(cells.size());
  std::vector<bool> done(cells.size(), false);
  std::mutex io_mutex;
  std::size_t computed = 0, finished = 0, cached = 0;
  double computed_seconds = 0.0, first_seconds = 0.0;  // the first computed cell may carry shared work
  std::atomic<bool> stop{false};
  std::string write_error;

  auto finished_rows = [&]() {
    std::vector<json> v;
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (done[i]) v.push_back(rows[i]);
    return v;
  };
  // The table holds nothing of "now": its provenance is derived from its rows.
  auto write_table = [&](bool complete) {
    const std::vector<json> v = finished_rows();
    json table = {{"experiment", name},
                  {"kind", kind->name()},
                  {"description", spec.value("description", "")},
                  {"spec_file", options.spec_file},
                  {"spec", spec},
                  {"provenance", table_provenance(v)},
                  {"complete", complete},
                  {"rows", v}};
    write_file_atomically(table_file.string(), table.dump(2) + "\n");
  };

  std::atomic<std::size_t> next{0};
  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(cells.size())));
  const int threads_per_job = std::max(1, omp_get_max_threads() / jobs);
  const std::string tag = "[" + name + "] ";
  auto worker = [&]() {
    omp_set_num_threads(threads_per_job);
    for (std::size_t i = next++; i < cells.size() && !stop; i = next++) {
      const auto& c = cells[i];
      const fs::path cell_file = out / "cells" / (c.id + ".json");
      if (!options.force && fs::exists(cell_file)) {
        try {
          json prev = read_json_file(cell_file.string());
          if (prev.value("status", "") != "error" && prev.value("params", json()) == resolved[i]) {
            std::lock_guard<std::mutex> guard(io_mutex);
            rows[i] = prev;
            done[i] = true;
            ++cached;
            ++finished;
            std::cerr << tag << "cell " << (i + 1) << "/" << cells.size() << " (" << c.label
                      << ") already done; skipped (use --force to re-run)\n";
            continue;
          }
        } catch (const std::exception&) {
          // An unreadable previous result is simply re-run.
        }
      }
      {
        std::lock_guard<std::mutex> guard(io_mutex);
        std::cerr << tag << "cell " << (i + 1) << "/" << cells.size() << " (" << c.label << ") started\n";
      }
      const auto t0 = std::chrono::steady_clock::now();
      json row;
      try {
        row = kind->run(resolved[i], registry, [&](const std::string& line) {
          std::lock_guard<std::mutex> guard(io_mutex);
          std::cerr << tag << "(" << c.label << ") " << line << "\n";
        });
      } catch (const std::exception& e) {
        row = {{"status", "error"}, {"error", e.what()}, {"errors", json::object()}, {"cost", json::object()}};
      }
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      row["id"] = c.id;
      row["label"] = c.label;
      row["params"] = resolved[i];
      row["cell_wall_seconds"] = secs;
      row["provenance"] = prov;
      std::lock_guard<std::mutex> guard(io_mutex);
      try {
        write_file_atomically(cell_file.string(), row.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
        rows[i] = row;
        done[i] = true;
        if (computed++ == 0) first_seconds = secs;
        else computed_seconds += secs;
        ++finished;
        write_table(false);
      } catch (const std::exception& e) {
        write_error = e.what();
        stop = true;
        break;
      }
      // One line per cell with an estimate of the time left (from the cells computed so far).
      const std::size_t left = cells.size() - finished;
      std::cerr << tag << "cell " << (i + 1) << "/" << cells.size() << " (" << c.label << ") "
                << row.value("status", "?") << " in " << format_seconds(secs) << "; " << finished << "/"
                << cells.size() << " done";
      // Time left: the mean of the computed cells times the cells left; the first computed cell is left out of
      // the mean once there are others (it may have done work the others reuse, e.g. a direct SPH reference).
      const double mean = computed > 1 ? computed_seconds / static_cast<double>(computed - 1) : first_seconds;
      if (left > 0) std::cerr << ", about " << format_seconds(mean * static_cast<double>(left) / jobs) << " left";
      std::cerr << (row.contains("error") ? ": " + row["error"].get<std::string>() : "") << "\n";
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (stop) {
    std::cerr << "error: " << write_error << "\nerror: the run stopped; " << computed
              << " cell(s) computed in this run are kept in " << (out / "cells").string() << "\n";
    return 1;
  }
  bool written = false;
  try {
    if (computed == 0 && table_unchanged(table_file, spec, finished_rows())) {
      std::cerr << tag << "nothing computed; " << table_file.string() << " left as it is\n";
    } else {
      write_table(true);
      written = true;
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\nerror: the table was not written; the cells are kept in "
              << (out / "cells").string() << "\n";
    return 1;
  }
  std::size_t failed = 0;
  for (const auto& r : rows) failed += r.value("status", "") == "error";
  std::cerr << tag << (written ? "wrote " : "kept ") << table_file.string() << " (" << cells.size() << " cells: " << computed
            << " computed, " << cached << " cached, " << failed << " failed)\n";
  return failed == 0 ? 0 : 1;
}

}  // namespace closurelab
