#include "experiments/runner/run_command.hpp"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "core/base/errors.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "experiments/runner/runner.hpp"
#include "experiments/runner/shards.hpp"
#include "experiments/runner/spec_checks.hpp"

namespace closurelab {

namespace {

bool env_set(const char* name) {
  const char* v = std::getenv(name);
  return v && *v;
}

const char* const run_usage =
    "usage: closurelab run SPEC.json [--out DIR] [--jobs N] [--force] [--store DIR] [--shard i/N]\n"
    "                 [--set KEY=VALUE ...] [--dry-run]\n"
    "       mpirun -n K closurelab run SPEC.json [--out DIR] [--force] [--store DIR] [--shard i/N]\n"
    "  Expands the experiment matrix of SPEC.json, validates every cell before running any, runs them and writes\n"
    "  DIR/cells/<id>.json per cell and the table DIR/<name>.json. A finished cell is not run again.\n"
    "  A cell's object merges into the base's (deep merge), unless it names another strategy (\"name\").\n"
    "  --out DIR      output folder (default: out/runs/<spec name>, git-ignored); locked while the run writes\n"
    "  --set KEY=VALUE  sets the dotted KEY (e.g. solver.kappa=0.1) in every cell, over the base, the axes and\n"
    "                 the cells; VALUE is read as JSON, else as a string; repeatable; validated like the spec\n"
    "  --dry-run      validates and prints every resolved cell (defaults filled in); runs and writes nothing\n"
    "  --jobs N       cells run at once (default 1); the OpenMP threads are shared among them\n"
    "  --force        recompute finished cells, and each direct SPH reference they use (once per run)\n"
    "  --store DIR    the reference store: direct SPH runs kept across cells, specs, runs and ranks (default\n"
    "                 $CLOSURELAB_STORE, else ~/.cache/closurelab/store); `closurelab store` lists it\n"
    "  --shard i/N    compute only the i-th of N cost-balanced shares (0 <= i < N) into DIR/cells and write no\n"
    "                 table; the N shards may run at once on one DIR; then `closurelab merge DIR`\n"
    "  --help         this text\n"
    "  Under mpirun (built with MPI) the K ranks share the cells, one at a time each, costliest first; rank 0\n"
    "  validates, hands out and writes.\n"
    "  Exit codes: 0 all cells ran, 1 a cell failed or a write failed, 2 bad input or the folder is in use.\n";

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

int run_command(int argc, char** argv, const Registry& registry) {
  if (wants_help(argc, argv)) {
    std::cout << run_usage;
    return 0;
  }
  RunOptions opt;
  opt.out_dir.clear();
  bool dry_run = false;
  std::vector<std::string> overrides;
  std::string spec_file, store_dir = default_reference_store_dir();
  bool store_given = false;
  for (int i = 0; i < argc; ++i) opt.command_line.append(i ? " " : "").append(argv[i]);
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    auto need = [&](const char* what) -> std::string {
      if (i + 1 >= argc) throw ConfigError("", std::string("option ") + a + " needs " + what);
      return argv[++i];
    };
    if (a == "--out") {
      opt.out_dir = need("a folder");
      if (opt.out_dir.empty()) throw ConfigError("", "--out needs a folder name, got ''");
    } else if (a == "--jobs") {
      const std::string v = need("a positive integer");
      std::size_t used = 0;
      try {
        opt.jobs = std::stoi(v, &used);
      } catch (...) {
        opt.jobs = 0;
      }
      if (opt.jobs < 1 || used != v.size()) throw ConfigError("", "--jobs needs a positive integer, got '" + v + "'");
    } else if (a == "--force") {
      opt.force = true;
    } else if (a == "--store") {
      store_dir = need("a folder");
      store_given = true;
      if (store_dir.empty()) throw ConfigError("", "--store needs a folder name, got ''");
    } else if (a == "--shard") {
      opt.shard = parse_shard(need("i/N"));
    } else if (a == "--set") {
      const std::string kv = need("KEY=VALUE");
      if (kv.find('=') == std::string::npos || kv[0] == '=')
        throw ConfigError("", "--set needs KEY=VALUE with a dotted KEY (e.g. solver.kappa=0.1), got '" + kv + "'");
      overrides.push_back(kv);
    } else if (a == "--dry-run") {
      dry_run = true;
    } else if (!a.empty() && a[0] == '-') {
      throw ConfigError("", "unknown option '" + a +
                                "'; valid: --out, --jobs, --force, --store, --shard, --set, --dry-run, --help");
    } else if (spec_file.empty()) {
      spec_file = a;
    } else {
      throw ConfigError("", "more than one spec file given ('" + spec_file + "', '" + a + "')");
    }
  }
  if (spec_file.empty()) throw ConfigError("", "run needs a SPEC.json");
  opt.spec_file = spec_file;
  json spec = read_json_file(spec_file);
  for (const std::string& o : overrides) apply_override(spec, o);
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
