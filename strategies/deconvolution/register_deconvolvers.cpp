#include "core/deconvolver.hpp"
#include "strategies/register_builtin.hpp"

namespace closurelab {
void register_deconvolvers(Registry&) {}
}  // namespace closurelab
