#pragma once
// Bond-integral weights of one bond onto the nodes of a tensor mesh, with periodic images: the geometric
// factor ∫₀¹ ψ_η(s(x − q_k) + (1 − s)(x − q_j)) ds of (2.13) (Appendix A), tabulated once per bond by the
// stress quadratures (positions are intact, §5.2). Images as in core/averaging/averaging.cpp (for_nodes_within), so the
// exact quadrature reproduces average_particles' interaction stress to round-off.
#include <omp.h>

#include <Eigen/Core>
#include <cstdint>
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

// Threads for one weighted sum over `entries` bond weights: one per 32,768 entries, at most OpenMP's. A smaller
// sum costs less than starting a parallel region and clearing and reducing a node buffer per thread: the reduced
// model's coarse quadrature at N/N_C = 16 (6,184 entries, 2,000 sums) took 0.094-0.105 s on two threads
// against 0.045 s on one.
inline int weighted_sum_threads(std::size_t entries) {
  constexpr std::size_t entries_per_thread = 32768;
  const std::size_t wanted = entries / entries_per_thread;
  const int most = omp_get_max_threads();
  return wanted < 1 ? 1 : wanted >= static_cast<std::size_t>(most) ? most : static_cast<int>(wanted);
}

// The bond weights of a set of bonds, tabulated once (CSR by bond), and the one weighted sum of both stress
// quadratures, (2.13) and (5.27): T_ab(node) = Σ_bonds f_a d_b w(bond, node) for the requested components.
class BondWeightTable {
 public:
  // Tabulates `bonds` bonds; append(p, out) appends bond p's (node, weight) entries. Bonds are visited in
  // parallel and stored in order.
  template <class Append>
  void tabulate(std::size_t bonds, int node_count, const std::vector<std::string>& components, Append append);
  // The sum over the bonds with force_and_bond(p) = (f, d) of bond p.
  template <class ForceAndBond>
  std::map<std::string, Eigen::VectorXd> accumulate(ForceAndBond force_and_bond) const;

  bool tabulated() const { return !start_.empty(); }
  std::size_t bonds() const { return start_.empty() ? 0 : start_.size() - 1; }
  long entries() const { return static_cast<long>(node_.size()); }

 private:
  std::vector<std::string> components_;
  std::vector<std::pair<int, int>> comp_index_;
  int node_count_ = 0;
  std::vector<std::int64_t> start_;
  std::vector<std::int32_t> node_;
  std::vector<double> value_;
};

template <class Append>
void BondWeightTable::tabulate(std::size_t bonds, int node_count, const std::vector<std::string>& components,
                               Append append) {
  comp_index_ = component_indices(components);
  components_ = components;
  node_count_ = node_count;
  const int nthreads = omp_get_max_threads();
  std::vector<std::vector<std::int32_t>> block_node(nthreads);
  std::vector<std::vector<double>> block_value(nthreads);
  std::vector<std::int64_t> count(bonds, 0);
#pragma omp parallel num_threads(nthreads)
  {
    const int t = omp_get_thread_num();
    BondWeights w;
#pragma omp for schedule(static)
    for (std::size_t p = 0; p < bonds; ++p) {
      w.clear();
      append(p, w);
      count[p] = static_cast<std::int64_t>(w.size());
      for (const auto& [n, b] : w) {
        block_node[t].push_back(n);
        block_value[t].push_back(b);
      }
    }
  }
  // schedule(static) gives each thread one contiguous, ordered block of bonds.
  start_.assign(bonds + 1, 0);
  for (std::size_t p = 0; p < bonds; ++p) start_[p + 1] = start_[p] + count[p];
  node_.clear();
  value_.clear();
  node_.reserve(start_[bonds]);
  value_.reserve(start_[bonds]);
  for (int t = 0; t < nthreads; ++t) {
    node_.insert(node_.end(), block_node[t].begin(), block_node[t].end());
    value_.insert(value_.end(), block_value[t].begin(), block_value[t].end());
  }
}

template <class ForceAndBond>
std::map<std::string, Eigen::VectorXd> BondWeightTable::accumulate(ForceAndBond force_and_bond) const {
  const int nc = static_cast<int>(comp_index_.size());
  const int nthreads = weighted_sum_threads(node_.size());
  const std::size_t np = bonds();
  std::vector<std::vector<double>> acc(nthreads, std::vector<double>(static_cast<std::size_t>(node_count_) * nc, 0.0));
#pragma omp parallel num_threads(nthreads)
  {
    auto& buf = acc[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::size_t p = 0; p < np; ++p) {
      const auto [f, d] = force_and_bond(p);
      double tab[4];
      for (int c = 0; c < nc; ++c) tab[c] = f[comp_index_[c].first] * d[comp_index_[c].second];
      for (std::int64_t e = start_[p]; e < start_[p + 1]; ++e) {
        double* out = &buf[static_cast<std::size_t>(node_[e]) * nc];
        const double b = value_[e];
        for (int c = 0; c < nc; ++c) out[c] += tab[c] * b;  // (2.13) / (5.27)
      }
    }
  }
  return reduce_node_buffers(acc, node_count_, components_);
}

}  // namespace closurelab
