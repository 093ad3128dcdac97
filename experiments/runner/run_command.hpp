#pragma once
// `closurelab run SPEC.json [--out DIR] [--jobs N] [--force] [--store DIR] [--shard i/N] [--set KEY=VALUE ...]
// [--dry-run]`: its options, the spec's --set overrides, the dry run that prints the resolved cells, and the
// default output folder (out/runs/<spec name>); the run itself is run_experiment (runner.hpp).
#include <cstring>

#include "core/base/registry.hpp"

namespace closurelab {

int run_command(int argc, char** argv, const Registry& registry);

// Whether any argument after the command is --help or -h (it wins wherever it stands).
inline bool wants_help(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
  return false;
}

}  // namespace closurelab
