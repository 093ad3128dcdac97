// The 2D force-density model's convective flux (solver.convective_stress; core/reduced/force_density_2d.hpp): the maps
// D_b(n, a) = m ∂_{q_b} ψ(x_n − q_a) / ρ̄_n over the fluid particles at their lattice sites, the rates
//   q_x = D_x (V_x V_x) + D_y (V_x V_y),   q_y = D_x (V_y V_x) + D_y (V_y V_y)   (products per particle),
// V = P r the reconstruction r interpolated to the particles, and Newton's iteration on the steady system with them.
// The rates are evaluated on the reconstruction's node pairs, at a cost that does not grow with the particles: each
// V_a is bilinear in r (four nodes), so (V_a)_b (V_a)_c = Σ_{j,l} P_aj P_al r_bj r_cl and, summed over the particles,
//   Σ_a D(n, a) V_a,b V_a,c = Σ_p T(n, p) π_bc(p),   T(n, p) = Σ_a D(n, a) S_a(p),
// over the node pairs p = {j, l} that share a cell, π_bc(p) = r_bj r_cl + r_bl r_cj (j ≠ l) or r_bj r_cj (j = l), S_a(p)
// the weight product of p in particle a (P_aj P_al, doubled where two of a's corners are one node). The same sum
// in another order (the golden Newton cell of tests/golden is bit-identical; the flux test of
// tests/numerical/test_force_density_convective.cpp holds it to the averaged momentum's rate); the particle maps
// stay for the steady Newton's Jacobian.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "core/base/repeated_timing.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "core/reduced/force_density_2d_assembly.hpp"

namespace closurelab {

using force_density_detail::equilibrated_steady_solve;

namespace {

// φ and φ' of the window at the nodes of an axis around q, periodic images summed (as axis_window), entries whose φ
// is below cutoff · φ(0) dropped: (node, φ, φ'), φ' with respect to the node's coordinate.
struct WindowEntry {
  int node;
  double value, derivative;
};
std::vector<WindowEntry> axis_window_and_derivative(const AveragingKernel& kernel, const UniformMesh1D& axis, double q,
                                                    double cutoff) {
  std::vector<WindowEntry> out;
  for_nodes_within(axis, q, kernel.support_radius(),
                   [&](int n, double d) { out.push_back({n, kernel.factor(d), kernel.factor_derivative(d)}); });
  std::sort(out.begin(), out.end(), [](const WindowEntry& a, const WindowEntry& b) { return a.node < b.node; });
  std::size_t k = 0;
  for (std::size_t u = 0; u < out.size(); ++u) {
    if (k > 0 && out[k - 1].node == out[u].node) {
      out[k - 1].value += out[u].value;
      out[k - 1].derivative += out[u].derivative;
    } else {
      out[k++] = out[u];
    }
  }
  out.resize(k);
  const double drop = cutoff * kernel.factor(0.0);
  out.erase(std::remove_if(out.begin(), out.end(), [&](const WindowEntry& e) { return e.value < drop; }), out.end());
  return out;
}

// max |v| over the velocity part (the first `count` entries) of a state.
double velocity_norm(const Eigen::VectorXd& z, Eigen::Index count) { return z.head(count).cwiseAbs().maxCoeff(); }

}  // namespace

void ForceDensitySolver2D::assemble_convective(const Scene& scene, const AveragingKernel& kernel,
                                               const ParticleSystem& lattice, const Eigen::VectorXd& rho_bar) {
  const double m = scene.particle_mass();
  for (std::size_t a = 0; a < lattice.size(); ++a)
    if (!fixed_[a]) fluid_.push_back(static_cast<int>(a));
  const auto nf = static_cast<Eigen::Index>(fluid_.size());
  std::vector<Eigen::Triplet<double>> tx, ty, tp;
  for (Eigen::Index k = 0; k < nf; ++k) {
    const auto a = static_cast<std::size_t>(fluid_[static_cast<std::size_t>(k)]);
    // ∂_{q_x} ψ(x_n − q_a) = −φ'(x_n − q_x) φ(y_n − q_y), and likewise in y.
    const auto wx = axis_window_and_derivative(kernel, coarse_.x, lattice.x[a], opt_.window_cutoff);
    const auto wy = axis_window_and_derivative(kernel, coarse_.y, lattice.y[a], opt_.window_cutoff);
    for (const WindowEntry& ey : wy)
      for (const WindowEntry& ex : wx) {
        const int n = coarse_.index(ex.node, ey.node);
        const double c = -m / rho_bar[n];
        tx.emplace_back(n, k, c * ex.derivative * ey.value);
        ty.emplace_back(n, k, c * ex.value * ey.derivative);
      }
    for (int u = 0; u < 4; ++u)
      if (interp_[a].weight[u] != 0.0) tp.emplace_back(k, interp_[a].node[u], interp_[a].weight[u]);
  }
  conv_dx_.resize(coarse_.size(), nf);
  conv_dy_.resize(coarse_.size(), nf);
  fluid_interp_.resize(nf, recon_.size());
  conv_dx_.setFromTriplets(tx.begin(), tx.end());
  conv_dy_.setFromTriplets(ty.begin(), ty.end());
  fluid_interp_.setFromTriplets(tp.begin(), tp.end());
  // The node pairs and S (fluid particles × pairs), then T_b = D_b S.
  std::map<std::pair<int, int>, int> pair_index;
  std::vector<Eigen::Triplet<double>> ts;
  const auto add = [&](Eigen::Index k, int j, int l, double w) {
    const auto key = std::minmax(j, l);
    const auto [it, fresh] = pair_index.try_emplace({key.first, key.second}, static_cast<int>(pairs_.size()));
    if (fresh) pairs_.push_back({key.first, key.second});
    ts.emplace_back(k, it->second, w);
  };
  for (Eigen::Index k = 0; k < nf; ++k) {
    const Interp& ip = interp_[static_cast<std::size_t>(fluid_[static_cast<std::size_t>(k)])];
    for (int u = 0; u < 4; ++u) {
      if (ip.weight[u] == 0.0) continue;
      add(k, ip.node[u], ip.node[u], ip.weight[u] * ip.weight[u]);
      for (int v = u + 1; v < 4; ++v)
        if (ip.weight[v] != 0.0)
          add(k, ip.node[u], ip.node[v], (ip.node[u] == ip.node[v] ? 2.0 : 1.0) * ip.weight[u] * ip.weight[v]);
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> weights(nf, static_cast<Eigen::Index>(pairs_.size()));
  weights.setFromTriplets(ts.begin(), ts.end());  // duplicates summed
  pairs_x_ = (conv_dx_ * weights).pruned();
  pairs_y_ = (conv_dy_ * weights).pruned();
}

void ForceDensitySolver2D::convective_rates(const Eigen::VectorXd& rx, const Eigen::VectorXd& ry, Eigen::VectorXd& qx,
                                            Eigen::VectorXd& qy) const {
  if (!opt_.convective_stress) {
    qx = qy = Eigen::VectorXd::Zero(coarse_.size());
    return;
  }
  const auto np = static_cast<Eigen::Index>(pairs_.size());
  Eigen::VectorXd pxx(np), pxy(np), pyy(np);
  for (Eigen::Index p = 0; p < np; ++p) {
    const auto [j, l] = pairs_[static_cast<std::size_t>(p)];
    if (j == l) {
      pxx[p] = rx[j] * rx[j];
      pxy[p] = rx[j] * ry[j];
      pyy[p] = ry[j] * ry[j];
    } else {
      pxx[p] = 2.0 * rx[j] * rx[l];
      pxy[p] = rx[j] * ry[l] + rx[l] * ry[j];
      pyy[p] = 2.0 * ry[j] * ry[l];
    }
  }
  qx = pairs_x_ * pxx + pairs_y_ * pxy;
  qy = pairs_x_ * pxy + pairs_y_ * pyy;
}

Eigen::MatrixXd ForceDensitySolver2D::to_reconstruction(const Eigen::SparseMatrix<double, Eigen::RowMajor>& d,
                                                        const Eigen::VectorXd& w) const {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(d.rows(), recon_.size());
  for (Eigen::Index n = 0; n < d.outerSize(); ++n)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(d, n); it; ++it) {
      const double c = it.value() * w[it.col()];
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator p(fluid_interp_, it.col()); p; ++p)
        out(n, p.col()) += c * p.value();
    }
  return out;
}

bool ForceDensitySolver2D::newton_convective(const Eigen::MatrixXd& big, const Eigen::VectorXd& rhs,
                                             const Eigen::MatrixXd& xv, const Eigen::VectorXd& x0v, bool minimum_norm,
                                             Eigen::VectorXd& z, std::string& issue) {
  // F(z) = big z − rhs + (q_x, q_y, 0) on the free rows; its Jacobian big + ∂q/∂z, with ∂q/∂v̄ through V = P (xv v̄ + x0v):
  //   ∂q_x/∂v̄_x = (D_x 2V_x + D_y V_y) P xv,  ∂q_x/∂v̄_y = D_y V_x P xv,
  //   ∂q_y/∂v̄_x = D_x V_y P xv,              ∂q_y/∂v̄_y = (D_x V_x + D_y 2V_y) P xv.
  const auto t0 = std::chrono::steady_clock::now();
  const auto f = static_cast<Eigen::Index>(free_.size());
  const auto free_rows = [&](const Eigen::MatrixXd& full) {
    Eigen::MatrixXd out(f, full.cols());
    for (Eigen::Index k = 0; k < f; ++k) out.row(k) = full.row(free_[static_cast<std::size_t>(k)]);
    return out;
  };
  for (int it = 1; it <= opt_.newton_max_iterations; ++it) {
    const Eigen::VectorXd rx = xv * z.segment(0, f) + x0v, ry = xv * z.segment(f, f) + x0v;
    Eigen::VectorXd qx, qy;
    convective_rates(rx, ry, qx, qy);
    Eigen::VectorXd residual = big * z - rhs;
    residual.segment(0, f) += on_free(qx);
    residual.segment(f, f) += on_free(qy);
    const Eigen::VectorXd vx = fluid_interp_ * rx, vy = fluid_interp_ * ry;
    const Eigen::MatrixXd dx_vx = to_reconstruction(conv_dx_, vx), dx_vy = to_reconstruction(conv_dx_, vy),
                          dy_vx = to_reconstruction(conv_dy_, vx), dy_vy = to_reconstruction(conv_dy_, vy);
    Eigen::MatrixXd jacobian = big;
    jacobian.block(0, 0, f, f) += free_rows(2.0 * dx_vx + dy_vy) * xv;
    jacobian.block(0, f, f, f) += free_rows(dy_vx) * xv;
    jacobian.block(f, 0, f, f) += free_rows(dx_vy) * xv;
    jacobian.block(f, f, f, f) += free_rows(dx_vx + 2.0 * dy_vy) * xv;
    Eigen::VectorXd step;
    if (!equilibrated_steady_solve(std::move(jacobian), -residual, step, issue, minimum_norm)) {
      issue = "Newton step " + std::to_string(it) + ": " + issue;
      return false;
    }
    z += step;
    newton_iterations_ = it;
    newton_last_step_ = velocity_norm(step, 2 * f) / std::max(velocity_norm(z, 2 * f), 1e-300);
    if (!z.allFinite()) break;
    if (newton_last_step_ <= opt_.newton_tolerance) {
      newton_seconds_ = seconds_since(t0);
      return true;
    }
  }
  newton_seconds_ = seconds_since(t0);
  std::ostringstream os;
  os << "Newton's iteration on the convective flux did not converge in " << newton_iterations_
     << " steps (last step " << newton_last_step_ << " of the state; solver.newton_tolerance "
     << opt_.newton_tolerance << ")";
  issue = os.str();
  return false;
}

}  // namespace closurelab
