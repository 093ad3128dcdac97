#pragma once
// `closurelab deconvolve --matrix A.mtx --rhs b.mtx ...`: deconvolution of a user system
// with any deconvolver of `registry` (the built-ins and whatever a user's executable registered).
#include "core/base/registry.hpp"
#include "experiments/runner/command_options.hpp"

namespace closurelab {
// Its options (command_options.hpp); --method lists the registry's deconvolvers.
CommandSpec deconvolve_command_spec(const Registry& registry);
int run_deconvolve_command(int argc, char** argv, const Registry& registry);
}
