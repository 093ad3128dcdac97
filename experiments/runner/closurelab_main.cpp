// The command-line program of closurelab (list, run, merge, seal, deconvolve, store, export), as a function that a
// user's executable calls with its own registration hook (experiments/runner/closurelab_main.hpp); the stock
// `closurelab` calls it with none (main.cpp). The commands with many options have files of their own:
//   closurelab list [family]
//   closurelab run SPEC.json [...]                  (run_command.cpp; also under mpirun -n K)
//   closurelab merge DIR
//   closurelab seal DIR [--dry-run]                 (seal_command.cpp)
//   closurelab store [--store DIR]
//   closurelab deconvolve --matrix A.mtx --rhs b.mtx [...]   (deconvolve_command.cpp)
//   closurelab export TABLE.json --csv               (export_command.cpp)
#include "experiments/runner/closurelab_main.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "build_info.hpp"
#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "experiments/runner/command_options.hpp"
#include "experiments/runner/deconvolve_command.hpp"
#include "experiments/runner/export_command.hpp"
#include "experiments/runner/run_command.hpp"
#include "experiments/runner/seal_command.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "experiments/runner/runner.hpp"
#include "experiments/runner/shards.hpp"

namespace closurelab {

namespace {

const char* const families = "kernel, deconvolver, quadrature, scene, experiment";

const CommandSpec& list_spec() {
  static const CommandSpec spec{
      "list", {{"FAMILY", false}},
      std::string("  Prints the registered strategies with their parameters (name, type, default, range: meaning).\n") +
          "  families: " + families,
      {}, ""};
  return spec;
}

const CommandSpec& merge_spec() {
  static const CommandSpec spec{
      "merge", {{"DIR"}},
      "  Writes the table DIR/<name>.json of a run made with --out DIR --shard i/N (every i), as a single run would\n"
      "  have written it. Every cell must be in DIR/cells, intact and sealed (cell_fnv1a64); the missing, damaged or\n"
      "  unsealed ones are listed with the shards to run (trusted cells of an older closurelab: closurelab seal DIR).",
      {},
      "  Exit codes: 0 written, 1 a cell had failed or a write failed, 2 missing cells, bad input or the folder in use."};
  return spec;
}

const CommandSpec& store_spec() {
  static const CommandSpec spec{
      "store", {},
      "  Lists the entries of the reference store (id, size, date, scene and what ended the run) and its total\n"
      "  size. Remove the folder to empty it.",
      {store_option()}, ""};
  return spec;
}

// One line per command, from the commands' own tables (their synopses), then how to get one command's usage.
void top_usage(std::ostream& os, const Registry& registry) {
  os << "closurelab " << build_info::version << " (" << build_info::git_commit << ")\n"
     << "usage:\n";
  for (const CommandSpec* c : {&list_spec(), &run_command_spec(), &merge_spec(), &seal_command_spec(), &store_spec(),
                               &export_command_spec()}) {
    std::istringstream lines(synopsis(*c));
    for (std::string l; std::getline(lines, l);) os << "  " << l << "\n";
  }
  std::istringstream lines(synopsis(deconvolve_command_spec(registry)));
  for (std::string l; std::getline(lines, l);) os << "  " << l << "\n";
  os << "  closurelab COMMAND --help    the usage of one command\n"
     << "  closurelab --version\n";
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
  if (wants_help(list_spec(), argc, argv)) {
    std::cout << usage(list_spec());
    return 0;
  }
  const std::string want = parse_command_line(list_spec(), argc, argv).positional(0);
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
    for (const ExperimentKind* k : reg.experiments.all()) {
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

int store_command(int argc, char** argv) {
  if (wants_help(store_spec(), argc, argv)) {
    std::cout << usage(store_spec());
    return 0;
  }
  const std::string dir = parse_command_line(store_spec(), argc, argv).value("--store", default_reference_store_dir());
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
  if (wants_help(merge_spec(), argc, argv)) {
    std::cout << usage(merge_spec());
    return 0;
  }
  const std::string dir = parse_command_line(merge_spec(), argc, argv).positional(0);
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line.append(i ? " " : "").append(argv[i]);
  return merge_shards(dir, registry, command_line);
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
  const std::string cmd = argc < 2 ? "" : argv[1];
  try {
    // One registry per process: the built-ins, then the user's entries (a name registered twice is a
    // std::logic_error naming it, exit 1).
    Registry registry;
    register_builtin_strategies(registry);
    register_builtin_experiments(registry);
    if (register_user) register_user(registry);
    if (argc < 2) {
      top_usage(std::cerr, registry);
      return 2;
    }
    if (cmd == "list") return stdout_checked(list_command(argc, argv, registry));
    if (cmd == "run") return run_command(argc, argv, registry);
    if (cmd == "merge") return merge_command(argc, argv, registry);
    if (cmd == "seal") return run_seal_command(argc, argv);
    if (cmd == "deconvolve") return run_deconvolve_command(argc, argv, registry);
    if (cmd == "store") return stdout_checked(store_command(argc, argv));
    if (cmd == "export") return run_export_command(argc, argv);
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      top_usage(std::cout, registry);
      return stdout_checked(0);
    }
    if (cmd == "--version") {
      std::cout << "closurelab " << build_info::version << " (" << build_info::git_commit << ")\n";
      return stdout_checked(0);
    }
    std::cerr << "error: unknown command '" << cmd << "'; known: list, run, merge, seal, deconvolve, store, export, "
                 "--help, --version\n";
    top_usage(std::cerr, registry);
    return 2;
  } catch (const UsageError& e) {  // a bad invocation: the message, then the command's synopsis
    std::cerr << "error: " << e.what() << "\n" << e.usage_lines();
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
