#pragma once
// A user's deconvolver: the Richardson iteration x_{k+1} = x_k + omega (b - A x_k), x_0 = 0, for a square A.
#include "core/base/registry.hpp"

namespace closurelab_example {

// Adds "richardson" to the deconvolver family of `registry`.
void register_richardson(closurelab::Registry& registry);

}  // namespace closurelab_example
