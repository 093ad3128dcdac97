#pragma once
// One registration function per strategy family; register_builtin_strategies() calls them all.
#include "core/base/registry.hpp"

namespace closurelab {
void register_kernels(Registry& r);        // strategies/kernels/
void register_deconvolvers(Registry& r);   // strategies/deconvolution/
void register_quadratures(Registry& r);    // strategies/quadrature/
void register_scenes(Registry& r);         // core/scenes/scenes.cpp
}  // namespace closurelab
