#pragma once
// Bond-integral weights of one bond onto the nodes of a tensor mesh, with periodic images: the geometric
// factor ∫₀¹ ψ_η(s(x − q_k) + (1 − s)(x − q_j)) ds of (2.13) (Appendix A), tabulated once per bond by the
// stress quadratures (positions are intact, §5.2). Images as in core/averaging.cpp (for_nodes_within), so the
// exact quadrature reproduces average_particles' interaction stress to round-off.
#include <Eigen/Core>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/particles.hpp"

namespace closurelab {

// (node, weight) entries of one bond.
using BondWeights = std::vector<std::pair<int, double>>;

// Appends the weights of the bond from q_j to q_j + d at every node (and every periodic image of the bond)
// within reach; entries of one node are summed.
void append_bond_weights(const AveragingKernel& kernel, const TensorMesh2D& mesh, const Vec2& qj, const Vec2& d,
                         BondWeights& out);

// The bond weight integrated over the bond's x-position (x-invariant fields, coarse quadrature):
// ∫ dR_x ∫₀¹ ψ(s(x − q_k) + (1 − s)(x − q_j)) ds = ∫₀¹ φ(y − q_j,y − s d_y) ds, the same for every node
// column. Appends the weights at the rows of `mesh` (flat index of column 0 .. nx−1 each get it).
void append_bond_weights_x_integrated(const AveragingKernel& kernel, const TensorMesh2D& mesh, double qj_y, double d_y,
                                      BondWeights& out);

// Throws ConfigError when the mesh's periodicity differs from the box's.
void check_mesh_matches_box(const TensorMesh2D& mesh, const PeriodicBox& box);

// Sums per-thread node buffers (node-major, `components.size()` values per node) into one field per component.
std::map<std::string, Eigen::VectorXd> reduce_node_buffers(const std::vector<std::vector<double>>& buffers,
                                                           int node_count, const std::vector<std::string>& components);

// Component names → (row, column) index pairs ("xx", "xy", "yx", "yy"; T_ab = Σ f_a d_b).
std::vector<std::pair<int, int>> component_indices(const std::vector<std::string>& components);

}  // namespace closurelab
