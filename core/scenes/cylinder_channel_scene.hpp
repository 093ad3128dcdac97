#pragma once
// The scene "cylinder-channel" (core/scenes/cylinder_channel_scene.cpp): a row of circular cylinders in a channel,
// periodic in x, walls in y, driven by a body force on the fluid; the first walled scene that is not x-invariant.

namespace closurelab {

struct Registry;

void register_cylinder_channel_scene(Registry& r);  // called from register_scenes (core/scenes/scenes.cpp)

}  // namespace closurelab
