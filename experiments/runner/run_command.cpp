#include "experiments/runner/run_command.hpp"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "experiments/runner/command_options.hpp"
#include "experiments/runner/runner.hpp"
#include "experiments/runner/shards.hpp"
#include "experiments/runner/spec_checks.hpp"

namespace closurelab {

namespace {

bool env_set(const char* name) {
  const char* v = std::getenv(name);
  return v && *v;
}

// `run --dry-run`: validates the spec and prints each cell (label, id, the resolved configuration with every
// default filled in); exit 0 when every cell is valid, 2 otherwise. Nothing is run or written.
int print_resolved_cells(const json& spec, const Registry& registry) {
  const auto matrix = validate_matrix(spec, registry);
  if (!matrix) return 2;
  std::cout << "experiment " << spec.at("name").get<std::string>() << " (kind " << matrix->kind->name() << "): "
            << matrix->cells.size() << " cell(s), all valid\n";
  for (std::size_t i = 0; i < matrix->cells.size(); ++i) {
    const MatrixCell& c = matrix->cells[i];
    std::cout << "cell " << c.id << " [" << c.label << "] (" << c.path << "):\n" << matrix->resolved[i].dump(2) << "\n";
  }
  if (!std::cout.flush()) {
    std::cerr << "error: cannot write the resolved cells to stdout\n";
    return 1;
  }
  return 0;
}

// Where `run` writes without --out: out/runs/<spec name> (git-ignored), never the tracked results/.
// (An invalid name is reported by the run's validation, before it writes.)
std::string default_out_dir(const json& spec) {
  try {
    check_spec_top_level(spec);
  } catch (const ConfigError&) {
    return "out/runs/unnamed";
  }
  return "out/runs/" + spec["name"].get<std::string>();
}

}  // namespace

// The options of `run`, declared once: its usage, parser and messages come from this table.
const CommandSpec& run_command_spec() {
  static const CommandSpec spec{
      "run",
      {{"SPEC.json"}},
      "  Expands the experiment matrix of SPEC.json, validates every cell before running any, runs them and writes\n"
      "  DIR/cells/<id>.json per cell and the table DIR/<name>.json. A finished cell is not run again.\n"
      "  A cell's object merges into the base's (deep merge), unless it names another strategy (\"name\").",
      {{"--out", "DIR", "output folder (default: out/runs/<spec name>, git-ignored); locked while the run writes"},
       {"--jobs", "N", "cells run at once (default 1); the OpenMP threads are shared among them", false, false,
        ValueForm::positive_integer},
       {"--force", "", "recompute finished cells, and each direct SPH reference they use (once per run)"},
       store_option(),
       {"--shard", "i/N",
        "compute only the i-th of N cost-balanced shares (0 <= i < N) into DIR/cells and write no\n"
        "table; the N shards may run at once on one DIR; then `closurelab merge DIR`",
        false, false, ValueForm::text, [](const std::string& v) { parse_shard(v); }},
       {"--set", "KEY=VALUE",
        "sets the dotted KEY (e.g. solver.kappa=0.1) in every cell, over the base, the axes and\n"
        "the cells; VALUE is read as JSON, else as a string; repeatable; validated like the spec",
        true, false, ValueForm::key_value},
       {"--memory-limit", "SIZE",
        "refuse at validation what needs more memory (e.g. 8GB, 512MiB; default: CLOSURELAB_MEMORY_LIMIT,\n"
        "else half the physical memory)",
        false, false, ValueForm::text, [](const std::string& v) { parse_byte_count(v, "--memory-limit"); }},
       {"--max-cells", "N",
        "refuse a matrix of more than N cells before expanding it (default: CLOSURELAB_MAX_CELLS, else 100000)",
        false, false, ValueForm::positive_integer},
       {"--dry-run", "", "validates and prints every resolved cell (defaults filled in); runs and writes nothing"},
       {"--strict", "", "exit 3 when a row's status is not ok (numerical_issue, no_convergence), after writing it"}},
      "  Under mpirun (built with MPI) the K ranks share the cells, one at a time each, costliest first; rank 0\n"
      "  validates, hands out and writes (--jobs > 1 with several ranks is refused).\n"
      "  Exit codes: 0 all cells ran, 1 a cell failed or a write failed, 2 bad input or the folder is in use,\n"
      "  3 with --strict a row is not ok.",
      {"mpirun -n K closurelab run SPEC.json [--out DIR] [--force] [--store DIR] [--shard i/N] [--set KEY=VALUE ...]"}};
  return spec;
}

int run_command(int argc, char** argv, const Registry& registry) {
  if (wants_help(run_command_spec(), argc, argv)) {
    std::cout << usage(run_command_spec());
    return 0;
  }
  const ParsedArgs args = parse_command_line(run_command_spec(), argc, argv);
  RunOptions opt;
  for (int i = 0; i < argc; ++i) opt.command_line.append(i ? " " : "").append(argv[i]);
  opt.out_dir = args.value("--out");
  if (args.has("--jobs")) opt.jobs = std::stoi(args.value("--jobs"));
  opt.force = args.has("--force");
  opt.strict = args.has("--strict");
  if (args.has("--shard")) opt.shard = parse_shard(args.value("--shard"));
  if (args.has("--memory-limit")) set_memory_limit_bytes(parse_byte_count(args.value("--memory-limit"), "--memory-limit"));
  if (args.has("--max-cells")) set_max_cells(std::strtoull(args.value("--max-cells").c_str(), nullptr, 10));
  const bool dry_run = args.has("--dry-run"), store_given = args.has("--store");
  const std::string store_dir = args.value("--store", default_reference_store_dir());
  const std::string spec_file = args.positional(0);
  opt.spec_file = spec_file;
  json spec = read_json_file(spec_file);
  for (const std::string& o : args.all("--set")) {
    const std::vector<std::string> replaced = apply_override(spec, o);
    for (const std::string& r : replaced) std::cerr << "note: --set " << o << " replaces what the spec varied: " << r << "\n";
    opt.overrides.push_back({{"set", o}, {"replaced", replaced}});
  }
  if (dry_run) return print_resolved_cells(spec, registry);
  if (opt.out_dir.empty()) opt.out_dir = default_out_dir(spec);
  configure_reference_store(store_dir, opt.force);
  opt.after_run_on_rank0 = [&] {  // rank 0 only: under mpirun the summary is printed once
    if (!store_given && !env_set("CLOSURELAB_STORE") && !env_set("HOME"))
      std::cerr << "note: neither CLOSURELAB_STORE nor HOME is set: the reference store is the folder " << store_dir
                << " under the working folder (set CLOSURELAB_STORE or pass --store to share one)\n";
    std::error_code ec;
    if (std::filesystem::is_directory(store_dir, ec))
      std::cerr << "reference store " << store_dir << ": " << reference_store().list().size() << " entries, "
                << reference_store().total_bytes() << " bytes\n";
  };
  return run_experiment(spec, registry, opt);
}

}  // namespace closurelab
