#pragma once
// The Taylor–Green vortex scene "taylor-green" (core/scenes/taylor_green_scene.cpp): PySPH's taylor_green.py, a
// doubly periodic box whose exact velocity decays as e^{−8π² t/Re}; its exact solution is Scene::taylor_green.

namespace closurelab {

struct Registry;

void register_taylor_green_scene(Registry& r);  // called from register_scenes (core/scenes/scenes.cpp)

}  // namespace closurelab
