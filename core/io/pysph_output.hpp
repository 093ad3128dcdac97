#pragma once
// PySPH's own output files as particle snapshots (PySPH 1.0, pysph/solver/output.py, HDFOutput), read as PySPH
// writes them: one file per dump (`<name>_<iteration>.hdf5`), holding
//   /solver_data                 attributes t, dt, count
//   /particles/<array>/arrays/<property>   one 1D dataset per property; attribute `stored` false (and length 0)
//                                for a property the run did not write
//   /particles/<array>/constants/...
// with one particle array per kind of particle (e.g. `fluid`, `solid`). The mapping onto a ParticleSnapshot:
//   x, y -> x, y;  u, v -> vx, vy;  m -> mass (each array needs these five stored)
//   phase -> phase where an array carries a `phase` property, else 0;
//   fixed -> the array's `fixed` property (nonzero: held at rest) where it has one; else by the array's name:
//            arrays named solid, wall, walls, boundary, obstacle or channel (any case, or starting with
//            "solid", "wall" or "boundary") are wall particles, the others move. has_fixed is true when any array
//            was so identified or carries `fixed`; a file with fluid arrays only leaves the walls to the scene,
//            as an H5Part file without `fixed` does;
//   tag  -> particles whose tag is not 0 (PySPH's remote and ghost copies, only in detailed dumps) are left out;
//   t    -> time.
// Arrays are concatenated in the order HDF5 lists them (by name); rho, p, h and the rest are not needed (the
// closure recomputes densities from positions and masses). Float32 properties are converted to double.
// PySPH's .npz output (written when h5py is missing) stores its metadata as pickled Python objects, which this
// reader does not parse: read_particle_snapshot refuses it with the one-line conversion to .hdf5.
#include <string>

#include "core/io/particle_snapshot.hpp"

namespace closurelab {

// True when `file` is an HDF5 file with the groups /particles and /solver_data of PySPH's output (false for
// H5Part, other HDF5 files and files that are not HDF5).
bool is_pysph_output(const std::string& file);

// The one time step of a PySPH output file. ConfigError naming the file, the array and the property on
// anything missing or malformed (and through check_particles on non-finite values, masses <= 0).
ParticleSnapshot read_pysph_output(const std::string& file);

// The message for PySPH's .npz output (what to run to get the .hdf5 layout instead).
std::string pysph_npz_refusal(const std::string& file);

}  // namespace closurelab
