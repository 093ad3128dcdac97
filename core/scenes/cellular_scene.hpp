#pragma once
// The cellular-flow scene "cellular" (core/scenes/cellular_scene.cpp): doubly periodic cells driven by a
// divergence-free force, or a Taylor–Green vortex; its exact velocity is Scene::cellular_mode.

namespace closurelab {

struct Registry;

void register_cellular_scene(Registry& r);  // called from register_scenes (core/scenes/scenes.cpp)

}  // namespace closurelab
