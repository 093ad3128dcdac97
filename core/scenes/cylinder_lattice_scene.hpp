#pragma once
// The scene "cylinder-lattice" (core/scenes/cylinder_lattice_scene.cpp): flow through a periodic square lattice
// of circular cylinders (a porous medium; Morris, Fox & Zhu, J. Comput. Phys. 136 (1997); Zhu, Fox & Morris,
// Int. J. Numer. Anal. Meth. Geomech. 23 (1999)), driven by a body force on the fluid; its reference is the Darcy
// permeability of the square array (core/scenes/square_array_stokes.hpp), Scene::permeability.

namespace closurelab {

struct Registry;

void register_cylinder_lattice_scene(Registry& r);

// The sound speed of a Stokes scene with solids (Morris, Fox & Zhu 1997, and ν/L for an underdamped cell; the
// reasoning at its use in cylinder_lattice_scene.cpp): factor · V, V² = max(U², νU/L, gL, ν²/L²), U the scene's
// velocity scale. cylinder-channel uses it too.
double solid_scene_sound_speed(double factor, double u, double nu, double g, double l);  // called from register_scenes (core/scenes/scenes.cpp)

}  // namespace closurelab
