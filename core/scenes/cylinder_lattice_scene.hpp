#pragma once
// The scene "cylinder-lattice" (core/scenes/cylinder_lattice_scene.cpp): flow through a periodic square lattice
// of circular cylinders (a porous medium; Morris, Fox & Zhu, J. Comput. Phys. 136 (1997); Zhu, Fox & Morris,
// Int. J. Numer. Anal. Meth. Geomech. 23 (1999)), driven by a body force on the fluid; its reference is the Darcy
// permeability of the square array (core/scenes/square_array_stokes.hpp), Scene::permeability.

namespace closurelab {

struct Registry;

void register_cylinder_lattice_scene(Registry& r);  // called from register_scenes (core/scenes/scenes.cpp)

}  // namespace closurelab
