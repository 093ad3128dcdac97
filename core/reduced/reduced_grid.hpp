#pragma once
// The meshes of the reduced model across an x-invariant scene (spacing Δ ≈ spacing_over_eta · η'):
//   coarse       the nodes where v̄ evolves: cell-centred on a periodic domain, on both wall surfaces and
//                evenly between them in a walled channel ((5.6): the wall-surface nodes);
//   data         the nodes whose v̄ is deconvolved: the coarse nodes, less the wall-surface nodes unless they
//                are data (their imposed v̄ = 0 is not an average);
//   fine         the lattice rows of the fluid;
//   stress_axis  where T_int is evaluated: the coarse nodes, or the mid-nodes for the staggered scheme.
// Cheap to build (no operator, no factorization): validation of a spec builds it, the solver builds it again.
#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

struct ReducedGrid {
  UniformMesh1D coarse, data, fine, stress_axis;
  bool periodic = false;
  bool walls_are_data = false;
};

// The coarse nodes across a walled channel: on both wall surfaces ((5.6)) and evenly between, at the spacing nearest
// target_spacing; ConfigError at /solver/spacing_over_eta when fewer than 4 intervals fit.
UniformMesh1D wall_to_wall_nodes(const Scene& scene, double target_spacing);

// ConfigError at /scene (not x-invariant) or /solver/spacing_over_eta (fewer than 4 coarse intervals).
ReducedGrid make_reduced_grid(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta,
                              bool staggered, bool walls_are_data);

// The one-column tensor mesh (x: the strip's period, one node) over a y-axis of the scene.
TensorMesh2D column_of(const Scene& scene, const UniformMesh1D& y_axis);

}  // namespace closurelab
