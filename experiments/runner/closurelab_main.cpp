// The command-line program of closurelab (list, run, merge, deconvolve, store, export), as a function that a user's executable
// calls with its own registration hook (experiments/runner/closurelab_main.hpp); the stock `closurelab` calls it
// with none (main.cpp).
//   closurelab list [family]
//   closurelab run SPEC.json [--out DIR] [--jobs N] [--force] [--store DIR] [--shard i/N]   (also under mpirun -n K)
//   closurelab merge DIR
//   closurelab store [--store DIR]
//   closurelab deconvolve --matrix A.mtx --rhs b.mtx [...]
#include "experiments/runner/closurelab_main.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include "build_info.hpp"
#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "experiments/runner/deconvolve_command.hpp"
#include "experiments/runner/export_command.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "experiments/runner/runner.hpp"
#include "experiments/runner/shards.hpp"
#include "experiments/runner/spec_checks.hpp"

namespace closurelab {

namespace {

const char* const families = "kernel, deconvolver, quadrature, scene, experiment";

void usage(std::ostream& os) {
  os << "closurelab " << build_info::version << " (" << build_info::git_commit << ")\n"
     << "usage:\n"
     << "  closurelab list [FAMILY]                        families: " << families << "\n"
     << "  closurelab run SPEC.json [--out DIR] [--jobs N] [--force] [--store DIR] [--shard i/N]\n"
     << "                 [--set KEY=VALUE ...] [--dry-run]\n"
     << "  mpirun -n K closurelab run SPEC.json [--out DIR] [--force] [--store DIR]\n"
     << "  closurelab merge DIR                            the table of a run made in shards\n"
     << "  closurelab store [--store DIR]                  the reference store's entries and size\n"
     << "  closurelab export TABLE.json --csv [--out FILE]  a results table as CSV, one record per row\n"
     << "  closurelab deconvolve --matrix A.mtx --rhs b.mtx [--x-true x.mtx] --method NAME [--param k=v ...]\n"
     << "                        [--noise-level d] [--out x.mtx]\n"
     << "  closurelab COMMAND --help                       the usage of one command\n";
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

const char* const merge_usage =
    "usage: closurelab merge DIR\n"
    "  Writes the table DIR/<name>.json of a run made with --out DIR --shard i/N (every i), as a single run would\n"
    "  have written it. Every cell must be in DIR/cells; the missing ones are listed with the shards to run.\n"
    "  Exit codes: 0 written, 1 a cell had failed or a write failed, 2 missing cells, bad input or the folder in use.\n";

const char* const store_usage =
    "usage: closurelab store [--store DIR]\n"
    "  Lists the entries of the reference store (id, size, date, scene and what ended the run) and its total\n"
    "  size. DIR defaults to $CLOSURELAB_STORE, else ~/.cache/closurelab/store. Remove the folder to empty it.\n";

const char* const list_usage =
    "usage: closurelab list [FAMILY]\n"
    "  Prints the registered strategies with their parameters (name, type, default, range: meaning).\n";

bool wants_help(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
  return false;
}

void print_params(const ParamSchema& params, const std::string& indent) {
  for (const auto& p : params) {
    std::cout << indent << p.name << " (" << to_string(p.type)
              << (p.default_value.is_null() ? ", required" : ", default " + p.default_value.dump()) << ")";
    if (p.min) std::cout << " " << (p.exclusive_min ? ">" : ">=") << " " << *p.min;
    if (p.max) std::cout << " <= " << *p.max;
    if (!p.choices.empty()) {
      std::cout << " one of";
      for (const auto& c : p.choices) std::cout << " " << c;
    }
    std::cout << ": " << p.description << "\n";
  }
}

int list_command(int argc, char** argv, const Registry& reg) {
  if (wants_help(argc, argv)) {
    std::cout << list_usage << "  families: " << families << "\n";
    return 0;
  }
  if (argc > 3) {
    std::cerr << "error: list takes at most one FAMILY, got '" << argv[3] << "'\n" << list_usage;
    return 2;
  }
  const std::string want = argc > 2 ? argv[2] : "";
  bool any = false;
  for (const FamilyBase* fam : reg.families()) {
    if (!want.empty() && want != fam->family_name()) continue;
    any = true;
    std::cout << fam->family_name() << ":\n";
    for (const auto& e : fam->entries()) {
      std::cout << "  " << e.name << " - " << e.description << "\n";
      print_params(e.params, "      ");
    }
  }
  if (want.empty() || want == "experiment") {
    any = true;
    std::cout << "experiment:\n";
    for (const ExperimentKind* k : known_experiment_kinds(reg)) {
      std::cout << "  " << k->name() << " - " << k->description() << "\n";
      for (const auto& s : k->sections()) {
        std::cout << "      " << s.key << ": " << s.description;
        if (!s.family.empty()) std::cout << " (parameters: closurelab list " << s.family << ")";
        std::cout << "\n";
        print_params(s.params, "          ");
      }
    }
  }
  if (!any) {
    std::cerr << "error: unknown family '" << want << "'; known: " << families << "\n";
    return 2;
  }
  return 0;
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
  const int code = run_experiment(spec, registry, opt);
  std::error_code ec;
  if (std::filesystem::is_directory(store_dir, ec))
    std::cerr << "reference store " << store_dir << ": " << reference_store().list().size() << " entries, "
              << reference_store().total_bytes() << " bytes\n";
  return code;
}

int store_command(int argc, char** argv) {
  if (wants_help(argc, argv)) {
    std::cout << store_usage;
    return 0;
  }
  std::string dir = default_reference_store_dir();
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--store") {
      if (i + 1 >= argc || argv[i + 1][0] == '\0') {
        std::cerr << "error: --store needs a folder name\n" << store_usage;
        return 2;
      }
      dir = argv[++i];
    } else {
      std::cerr << "error: unknown argument '" << a << "'; valid: --store DIR, --help\n" << store_usage;
      return 2;
    }
  }
  const ReferenceStore store(dir);
  std::cout << "reference store " << dir << "\n";
  const std::vector<StoreEntryInfo> entries = store.list();
  for (const StoreEntryInfo& e : entries) {
    std::cout << "  " << e.id << "  " << e.bytes << " bytes  ";
    if (!e.problem.empty()) {
      std::cout << "unreadable (" << e.problem << ")\n";
      continue;
    }
    std::cout << e.computed << "  " << e.key.value("kind", "?");
    if (e.key.contains("scene")) std::cout << " " << e.key["scene"].value("name", "?");
    std::cout << " (" << e.status << ")\n";
  }
  std::cout << "total " << entries.size() << " entries, " << store.total_bytes() << " bytes\n";
  return 0;
}

int merge_command(int argc, char** argv, const Registry& registry) {
  if (wants_help(argc, argv)) {
    std::cout << merge_usage;
    return 0;
  }
  if (argc != 3 || argv[2][0] == '-') {
    std::cerr << "error: merge takes one folder DIR\n" << merge_usage;
    return 2;
  }
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line.append(i ? " " : "").append(argv[i]);
  return merge_shards(argv[2], registry, command_line);
}

}  // namespace

// A command's printed output must reach its reader: flushed and checked (stdout on a full disk or /dev/full is
// an error, exit 1, not a silent success).
int stdout_checked(int rc) {
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "error: cannot write to standard output: " << std::strerror(errno) << "\n";
    return rc == 0 ? 1 : rc;
  }
  return rc;
}

int closurelab_main(int argc, char** argv, const UserRegistration& register_user) {
  if (argc < 2) {
    usage(std::cerr);
    return 2;
  }
  const std::string cmd = argv[1];
  try {
    // One registry per process: the built-ins, then the user's entries (a name registered twice is a
    // std::logic_error naming it, exit 1).
    Registry registry;
    register_builtin_strategies(registry);
    if (register_user) register_user(registry);
    if (cmd == "list") return stdout_checked(list_command(argc, argv, registry));
    if (cmd == "run") return run_command(argc, argv, registry);
    if (cmd == "merge") return merge_command(argc, argv, registry);
    if (cmd == "deconvolve") return run_deconvolve_command(argc, argv, registry);
    if (cmd == "store") return stdout_checked(store_command(argc, argv));
    if (cmd == "export") return run_export_command(argc, argv);
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      usage(std::cout);
      return stdout_checked(0);
    }
    if (cmd == "--version") {
      std::cout << "closurelab " << build_info::version << " (" << build_info::git_commit << ")\n";
      return stdout_checked(0);
    }
    std::cerr << "error: unknown command '" << cmd << "'; known: list, run, merge, deconvolve, store, export, --help, "
                 "--version\n";
    usage(std::cerr);
    return 2;
  } catch (const ConfigError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace closurelab
