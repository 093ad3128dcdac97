#pragma once
// `closurelab run SPEC.json [options]`: its options (one table, run_command_spec), the spec's --set overrides, the dry run that prints the resolved cells, and the
// default output folder (out/runs/<spec name>); the run itself is run_experiment (runner.hpp).
#include "core/base/registry.hpp"
#include "experiments/runner/command_options.hpp"

namespace closurelab {

// The options of `run` (command_options.hpp): usage, parsing and messages.
const CommandSpec& run_command_spec();
int run_command(int argc, char** argv, const Registry& registry);

}  // namespace closurelab
