// closurelab: the command-line entry point.
//   closurelab list [family]
//   closurelab run SPEC.json [--out DIR] [--jobs N] [--force]
//   closurelab deconvolve --matrix A.mtx --rhs b.mtx [...]
#include <cstring>
#include <iostream>
#include <string>

#include "build_info.hpp"
#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "experiments/runner/deconvolve_command.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/runner.hpp"

using namespace closurelab;

namespace {

void usage(std::ostream& os) {
  os << "closurelab " << build_info::version << " (" << build_info::git_commit << ")\n"
     << "usage:\n"
     << "  closurelab list [family]                        families: kernel, deconvolver, quadrature, scene, experiment\n"
     << "  closurelab run SPEC.json [--out DIR] [--jobs N] [--force]\n"
     << "  closurelab deconvolve --matrix A.mtx --rhs b.mtx [--x-true x.mtx] --method NAME [--param k=v ...]\n"
     << "                        [--noise-level d] [--out x.mtx]\n";
}

int list_command(int argc, char** argv) {
  const Registry& reg = builtin_registry();
  const std::string want = argc > 2 ? argv[2] : "";
  bool any = false;
  for (const FamilyBase* fam : reg.families()) {
    if (!want.empty() && want != fam->family_name()) continue;
    any = true;
    std::cout << fam->family_name() << ":\n";
    for (const auto& e : fam->entries()) {
      std::cout << "  " << e.name << " - " << e.description << "\n";
      for (const auto& p : e.params) {
        std::cout << "      " << p.name << " (" << to_string(p.type)
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
  }
  if (want.empty() || want == "experiment") {
    any = true;
    std::cout << "experiment:\n";
    for (const auto& k : experiment_kinds()) std::cout << "  " << k->name() << " - " << k->description() << "\n";
  }
  if (!any) {
    std::cerr << "error: unknown family '" << want << "'; known: kernel, deconvolver, quadrature, scene, experiment\n";
    return 2;
  }
  return 0;
}

int run_command(int argc, char** argv) {
  RunOptions opt;
  std::string spec_file;
  for (int i = 0; i < argc; ++i) opt.command_line.append(i ? " " : "").append(argv[i]);
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    auto need = [&](const char* what) -> std::string {
      if (i + 1 >= argc) throw ConfigError("", std::string("option ") + a + " needs " + what);
      return argv[++i];
    };
    if (a == "--out") {
      opt.out_dir = need("a folder");
    } else if (a == "--jobs") {
      const std::string v = need("a positive integer");
      try {
        opt.jobs = std::stoi(v);
      } catch (...) {
        opt.jobs = 0;
      }
      if (opt.jobs < 1) throw ConfigError("", "--jobs needs a positive integer, got '" + v + "'");
    } else if (a == "--force") {
      opt.force = true;
    } else if (!a.empty() && a[0] == '-') {
      throw ConfigError("", "unknown option '" + a + "'");
    } else if (spec_file.empty()) {
      spec_file = a;
    } else {
      throw ConfigError("", "more than one spec file given ('" + spec_file + "', '" + a + "')");
    }
  }
  if (spec_file.empty()) throw ConfigError("", "run needs a SPEC.json");
  opt.spec_file = spec_file;
  const json spec = read_json_file(spec_file);
  return run_experiment(spec, builtin_registry(), opt);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(std::cerr);
    return 2;
  }
  const std::string cmd = argv[1];
  try {
    if (cmd == "list") return list_command(argc, argv);
    if (cmd == "run") return run_command(argc, argv);
    if (cmd == "deconvolve") return run_deconvolve_command(argc, argv);
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      usage(std::cout);
      return 0;
    }
    if (cmd == "--version") {
      std::cout << "closurelab " << build_info::version << " (" << build_info::git_commit << ")\n";
      return 0;
    }
    std::cerr << "error: unknown command '" << cmd << "'\n";
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
