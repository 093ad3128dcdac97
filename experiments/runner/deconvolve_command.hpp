#pragma once
// `closurelab deconvolve --matrix A.mtx --rhs b.mtx ...`: deconvolution of a user system (deconvolution issue)
// with any deconvolver of `registry` (the built-ins and whatever a user's executable registered).
#include "core/base/registry.hpp"

namespace closurelab {
int run_deconvolve_command(int argc, char** argv, const Registry& registry);
}
