#pragma once
// The two-phase layered channel of §7 (DESIGN.md §5, "layered-two-phase"): layers of a less viscous fluid
// (phase 1) in a more viscous one (phase 0) between zero-velocity walls, van der Waals EOS (7.1).
#include <string>
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {

struct Registry;

// Less-viscous layers in fluid rows of the scene's lattice (row 0 at the lower wall): each layer covers rows
// [start, start + width).
struct LayerLayout {
  std::vector<int> start_rows;
  int width = 0;
};

// The layout of resolved scene parameters: "case1".."case3" (DESIGN.md §5, rows of the 192-row lattice,
// scaled by n_y/192 and rounded) or "custom" (layer_rows and layer_width in rows of the scene's own lattice).
// Throws ConfigError (paths relative to the scene) if a layer vanishes, layers overlap or touch, or a layer
// leaves no row of the more viscous fluid between it and a wall.
LayerLayout layered_layout(const json& params);

void register_layered_scene(Registry& r);  // called from register_scenes (core/scenes/scenes.cpp)

}  // namespace closurelab
