#pragma once
// The 2D force-density model's assembly helpers (core/reduced/force_density_2d.cpp only): a scratch row over the
// reconstruction nodes, the window's 1D factor on an axis and the weighted first difference over the reconstruction
// mesh's links (the prior of first_difference_zero_ends), and the transport-velocity linearisation's solid-particle
// data (force_density_2d_transport.cpp). The lattice's pair stencil: core/sph/lattice_stencil.hpp.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/lattice_stencil.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab::force_density_detail {

// A row over the reconstruction nodes, accumulated densely and read back sparsely.
class ScratchRow {
 public:
  explicit ScratchRow(Eigen::Index n) : value_(Eigen::VectorXd::Zero(n)), seen_(static_cast<std::size_t>(n), 0) {}
  void add(int node, double v) {
    if (!seen_[static_cast<std::size_t>(node)]) {
      seen_[static_cast<std::size_t>(node)] = 1;
      touched_.push_back(node);
    }
    value_[node] += v;
  }
  // Calls f(node, value) for each entry, then clears.
  template <class F>
  void drain(F f) {
    for (int n : touched_) {
      if (value_[n] != 0.0) f(n, value_[n]);
      value_[n] = 0.0;
      seen_[static_cast<std::size_t>(n)] = 0;
    }
    touched_.clear();
  }

 private:
  Eigen::VectorXd value_;
  std::vector<std::uint8_t> seen_;
  std::vector<int> touched_;
};

// The Gaussian window's 1D factor at the nodes of a periodic axis around q, periodic images summed; factors below
// cutoff · φ(0) are dropped.
inline std::vector<std::pair<int, double>> axis_window(const AveragingKernel& kernel, const UniformMesh1D& axis, double q,
                                                double cutoff) {
  std::vector<std::pair<int, double>> out;
  for_nodes_within(axis, q, kernel.support_radius(), [&](int n, double d) { out.emplace_back(n, kernel.factor(d)); });
  // for_nodes_within visits each image separately: merge the images of one node, then drop the tail.
  std::sort(out.begin(), out.end());
  std::size_t k = 0;
  for (std::size_t u = 0; u < out.size(); ++u) {
    if (k > 0 && out[k - 1].first == out[u].first)
      out[k - 1].second += out[u].second;
    else
      out[k++] = out[u];
  }
  out.resize(k);
  const double drop = cutoff * kernel.factor(0.0);
  out.erase(std::remove_if(out.begin(), out.end(), [&](const auto& e) { return e.second < drop; }), out.end());
  return out;
}

// The weighted first difference over the links of the reconstruction mesh (ForwardOperator::difference_links): one row
// per pair of neighbouring nodes (x and y; wrapped along a periodic axis; none along an axis of one node) with an
// unknown at either end, √w (x_q − x_p), a node that is no unknown being a known zero (the solid's velocity) and
// contributing no entry. w = weight(p, q) · (h_y / h_x)² for an x-link, weight(p, q) for a y-link: ‖Lx‖² is then the
// Dirichlet energy Σ w |∇x|² h_x h_y up to the constant h_x / h_y. `unknown_of`: each node's unknown, or −1.
template <class Weight>
Eigen::SparseMatrix<double> link_differences(const TensorMesh2D& mesh, const std::vector<int>& unknown_of, int unknowns,
                                             Weight weight) {
  std::vector<Eigen::Triplet<double>> t;
  int row = 0;
  const double x_factor = std::pow(mesh.y.spacing / mesh.x.spacing, 2);
  const auto link = [&](int p, int q, double factor) {
    const int up = unknown_of[static_cast<std::size_t>(p)], uq = unknown_of[static_cast<std::size_t>(q)];
    if (up < 0 && uq < 0) return;
    const double s = std::sqrt(factor * weight(p, q));
    if (up >= 0) t.emplace_back(row, up, -s);
    if (uq >= 0) t.emplace_back(row, uq, s);
    ++row;
  };
  const int nx = mesh.nx(), ny = mesh.ny();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (nx > 1 && (i + 1 < nx || mesh.x.periodic)) link(mesh.index(i, j), mesh.index((i + 1) % nx, j), x_factor);
      if (ny > 1 && (j + 1 < ny || mesh.y.periodic)) link(mesh.index(i, j), mesh.index(i, (j + 1) % ny), 1.0);
    }
  Eigen::SparseMatrix<double> l(row, unknowns);
  l.setFromTriplets(t.begin(), t.end());
  return l;
}

// What the transport-velocity pair forces need beyond the lattice stencil (the header's formulation): each solid
// site's Shepard weights W_wf / Σ_f W_wf over its fluid neighbours (SetWallVelocity, SolidWallPressureBC; none where
// Σ_f W_wf is at most 1e-12, as the engine) and its hydrostatic pressure g(x_w) · Σ_f ρ_f (x_w − x_f) W_wf / Σ_f W_wf
// at rest, the volumes V² of a fluid (1/n0²) and a wall particle (ε'⁴), η / μ = ρ_rest / ρ0, ε = 0.01 h², and the
// rest pressure's share 2 P0 / n0³ of the pressure coefficient.
struct TransportLinearisation {
  std::vector<std::vector<std::pair<int, double>>> shepard;
  std::vector<double> hydrostatic;
  double vol2_fluid = 0.0, vol2_wall = 0.0, eta_per_mu = 0.0, eps = 0.0, rest_volume_term = 0.0;
};
// `site`: the particle of each lattice site (j n_x + i); `n0`, `p0`: the lattice's number density and pressure at rest.
TransportLinearisation transport_linearisation(const Scene& scene, const ParticleSystem& lattice,
                                               const std::vector<int>& site, const std::vector<LatticeOffset>& stencil,
                                               double n0, double p0);

// big z = rhs by LU of the equilibrated system (force_density_2d_solve.cpp): false, the reason in `issue`, when it is
// singular to working precision; with `minimum_norm`, the minimum-norm solution of a rank-deficient system.
bool equilibrated_steady_solve(Eigen::MatrixXd big, const Eigen::VectorXd& rhs, Eigen::VectorXd& z, std::string& issue,
                               bool minimum_norm);

}  // namespace closurelab::force_density_detail
