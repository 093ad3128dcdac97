#pragma once
// The lid-driven cavity scene "lid-driven-cavity" (core/scenes/cavity_scene.cpp): PySPH's cavity.py, a square of
// fluid inside fixed walls whose top one slides; its geometry is Scene::cavity.

namespace closurelab {

struct Registry;

void register_cavity_scene(Registry& r);  // called from register_scenes (core/scenes/scenes.cpp)

}  // namespace closurelab
