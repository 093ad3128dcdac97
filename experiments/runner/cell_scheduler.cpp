#include "experiments/runner/cell_scheduler.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <optional>
#include <thread>

#include "experiments/kinds/experiment_kind.hpp"

namespace closurelab {

void log_line(const std::string& line) {
  static std::mutex m;
  std::lock_guard<std::mutex> guard(m);
  std::cerr << line << "\n";
}

json compute_cell(const CellTask& task, const Registry& registry, json provenance, int threads,
                  const RankGroup& group) {
  // Appended rather than "[" + name: GCC 12 reports a false -Wrestrict on a literal + std::string&& here.
  std::string tag = "[";
  tag += task.at("experiment").get<std::string>();
  tag += "] ";
  const std::string label = task.at("label").get<std::string>();
  const std::string where = group.size() > 1 ? " on rank " + std::to_string(group.rank()) : "";
  const std::string cell = "cell " + std::to_string(task.at("index").get<std::size_t>() + 1) + "/" +
                           std::to_string(task.at("total").get<std::size_t>()) + " (" + label + ")";
  log_line(tag + cell + " started" + where);
  const json& resolved = task.at("resolved");
  const auto t0 = std::chrono::steady_clock::now();
  json row;
  try {
    const ExperimentKind& kind = registry.experiments.get(task.at("kind").get<std::string>(), "/kind");
    row = kind.run(resolved, registry, [&](const std::string& line) { log_line(tag + "(" + label + ") " + line); });
  } catch (const std::exception& e) {
    row = {{"status", "error"}, {"error", e.what()}, {"errors", json::object()}, {"cost", json::object()}};
  }
  row["id"] = task.at("id");
  row["label"] = label;
  row["params"] = resolved;
  row["cell_wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  provenance["threads"] = threads;
  provenance["ranks"] = group.size();
  provenance["rank"] = group.rank();
  row["provenance"] = provenance;
  return row;
}

std::vector<std::size_t> hand_out_order(const std::vector<std::size_t>& cells, const std::vector<double>& costs,
                                        int slots) {
  std::vector<std::size_t> order = cells;
  if (slots > 1)
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
  return order;
}

void schedule_cells(const std::vector<CellTask>& tasks, int jobs, int threads_per_job, const Registry& registry,
                    const json& provenance, const RankGroup& group,
                    const std::function<bool(const CellTask&, const json&)>& on_row) {
  std::mutex queue_mutex, row_mutex;
  std::size_t next = 0;
  bool stop = false;
  auto take = [&]() -> std::optional<std::size_t> {
    std::lock_guard<std::mutex> guard(queue_mutex);
    if (stop || next >= tasks.size()) return std::nullopt;
    return next++;
  };
  auto deliver = [&](const CellTask& task, const json& row) {
    std::lock_guard<std::mutex> guard(row_mutex);
    if (!on_row(task, row)) {
      std::lock_guard<std::mutex> q(queue_mutex);
      stop = true;
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j)
    pool.emplace_back([&]() {
      omp_set_num_threads(threads_per_job);
      while (const auto i = take())
        deliver(tasks[*i], compute_cell(tasks[*i], registry, provenance, threads_per_job, group));
    });
  // The other ranks, served from this (the calling) thread; the task sent to each rank pairs it with its row.
  std::vector<std::size_t> sent(static_cast<std::size_t>(group.size()), 0);
  group.serve(
      [&](int rank) -> std::optional<std::string> {
        const auto i = take();
        if (!i) return std::nullopt;
        sent[static_cast<std::size_t>(rank)] = *i;
        return tasks[*i].dump(-1, ' ', false, json::error_handler_t::replace);
      },
      [&](const std::string& text, int rank) {
        deliver(tasks[sent[static_cast<std::size_t>(rank)]], json::parse(text));
      });
  for (auto& t : pool) t.join();
}

void work_on_cells(const Registry& registry, const json& provenance, const RankGroup& group) {
  const int threads = omp_get_max_threads();
  group.work([&](const std::string& text) {
    const CellTask task = json::parse(text);
    return compute_cell(task, registry, provenance, threads, group)
        .dump(-1, ' ', false, json::error_handler_t::replace);
  });
}

}  // namespace closurelab
