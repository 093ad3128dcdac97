#pragma once
// Averaged pair forces as affine maps of the reconstruction (the reduced model's x-invariant scenes). With the
// particles fixed on the lattice, the pressure part and the factor (μ_i+μ_j)F/(n_i n_j) of (5.1) do not change,
// so the x-force on any particle is affine in the fluid velocities, and in an x-invariant flow those are a
// function of y alone: Σ_{a∈S} s f_a^x ψ(node − q_a) = offset + M · V(rows). M is probed once with the real pair
// forces on the narrowest strip (per unit length, like ρ̄ and F̄ (2.14)), in two pair sweeps; each use then costs
// O(nodes × rows).
//   - the wall constraint forces F_c: S = the wall particles within reach of the fluid, s = −1 (the force that
//     holds them at rest), rows = the fluid rows within reach of a wall (DESIGN.md §6);
//   - the force density of the exact averaged balance: S = the fluid particles, s = +1, rows = every fluid row;
//     Σ_F ψ f_a is the divergence of (2.13) plus F_c, exactly.
#include <Eigen/Core>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/particles.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

struct AveragedForceMap {
  Eigen::VectorXd offset;       // at the nodes, for V = 0
  Eigen::MatrixXd map;          // nodes × rows
  std::vector<Vec2> rows;       // one sample point (x = 0, y of the row) per column
  Eigen::VectorXd apply(const Eigen::VectorXd& row_velocity) const { return offset + map * row_velocity; }
};

// The wall constraint forces F_c at `nodes` (a walled scene).
AveragedForceMap wall_constraint_force_map(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes);
// The force density Σ_F ψ(node − q_a) f_a^x of the fluid particles at `nodes`.
AveragedForceMap fluid_force_density_map(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes);
// The same map probed on another particle state of the whole box (its positions; the velocities are set aside):
// e.g. the direct run's final particles, whose rows have slid against each other (the sheared lattice of the
// error budget's positions oracle). Rows are the particles' nearest lattice rows, sampled at the row's lattice y;
// the weights are the x-average over the box, φ(y_node − y_a) / l_x, exact for any x-distribution.
AveragedForceMap fluid_force_density_map_at(const Scene& scene, const AveragingKernel& kernel, const UniformMesh1D& nodes,
                                            const ParticleSystem& positions);

}  // namespace closurelab
