#include "core/averaging/averaging.hpp"

#include "core/averaging/bond_weights.hpp"

#include <omp.h>

#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/base/errors.hpp"

namespace closurelab {

std::pair<int, int> component_index(const std::string& c) {
  if (c.size() != 2 || (c[0] != 'x' && c[0] != 'y') || (c[1] != 'x' && c[1] != 'y'))
    throw ConfigError("", "unknown tensor component '" + c + "'; known: xx, xy, yx, yy");
  return {c[0] == 'x' ? 0 : 1, c[1] == 'x' ? 0 : 1};
}

TensorMesh2D column_mesh(const PeriodicBox& box, double spacing) {
  const int n = std::max(1, static_cast<int>(std::round(box.ly / spacing)));
  return TensorMesh2D{UniformMesh1D{0.0, box.lx, 1, box.periodic_x, box.lx},
                      UniformMesh1D::cell_centred(0.0, box.ly, n, box.periodic_y)};
}

namespace {

// One axis's window factors of a particle at coordinate q, φ(node − q) summed over the axis's periodic images,
// remembered by q: the particles of a lattice share n_x x-values and n_y y-values, and a column narrower than the
// window has many images per particle (r/L_x of them: 32 at n_y = 1536, η' = L/16, twelve columns), so each
// distinct coordinate is evaluated once. Up to kRemembered coordinates per axis (then evaluated afresh: disordered
// particles share none); the weights are the same bits either way.
class AxisWeights {
 public:
  AxisWeights(const AveragingKernel& kernel, const UniformMesh1D& axis) : kernel_(kernel), axis_(axis) {}
  const std::vector<std::pair<int, double>>& at(double q) {
    if (const auto it = remembered_.find(q); it != remembered_.end()) return it->second;
    std::vector<std::pair<int, double>>& w = remembered_.size() < kRemembered ? remembered_[q] : scratch_;
    w.clear();
    for_nodes_within(axis_, q, kernel_.support_radius(), [&](int i, double d) {
      const double v = kernel_.factor(d);
      for (auto& e : w)
        if (e.first == i) return void(e.second += v);
      w.emplace_back(i, v);
    });
    return w;
  }

 private:
  static constexpr std::size_t kRemembered = 1 << 14;
  const AveragingKernel& kernel_;
  const UniformMesh1D& axis_;
  std::unordered_map<double, std::vector<std::pair<int, double>>> remembered_;
  std::vector<std::pair<int, double>> scratch_;
};

void check_mesh_axis(const UniformMesh1D& a, bool box_periodic, double box_length, const char* name) {
  if (a.periodic != box_periodic || (a.periodic && std::abs(a.period - box_length) > 1e-12 * box_length))
    throw ConfigError("", std::string("mesh ") + name + "-axis periodicity does not match the box");
}

}  // namespace

MesoFields average_particles(const ParticleSystem& ps, const PeriodicBox& box, const AveragingKernel& kernel,
                             const TensorMesh2D& mesh, const AveragingRequest& req, const std::vector<PairForce>& pairs,
                             const std::function<double(double)>& force_x) {
  check_mesh_axis(mesh.x, box.periodic_x, box.lx, "x");
  check_mesh_axis(mesh.y, box.periodic_y, box.ly, "y");
  const int nn = mesh.size();
  MesoFields out;
  out.rho = Eigen::VectorXd::Zero(nn);
  out.mom_x = Eigen::VectorXd::Zero(nn);
  out.mom_y = Eigen::VectorXd::Zero(nn);
  if (req.external) {
    if (!force_x) throw ConfigError("", "external force requested without a body force");
    out.fx = Eigen::VectorXd::Zero(nn);
    out.fy = Eigen::VectorXd::Zero(nn);
  }
  // Separable window weights: ψ(node − q) = φ(Δx) φ(Δy), summed over images per axis.
  AxisWeights x_weights(kernel, mesh.x), y_weights(kernel, mesh.y);
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const auto& w_x = x_weights.at(ps.x[a]);
    const auto& w_y = y_weights.at(ps.y[a]);
    const double m = ps.mass[a];
    const double fext = (req.external && !ps.fixed[a]) ? m * force_x(ps.y[a]) : 0.0;
    for (const auto& [j, wy] : w_y)
      for (const auto& [i, wx] : w_x) {
        const int n = mesh.index(i, j);
        const double psi = wx * wy;
        out.rho[n] += m * psi;
        out.mom_x[n] += m * ps.vx[a] * psi;
        out.mom_y[n] += m * ps.vy[a] * psi;
        if (req.external) out.fx[n] += fext * psi;
      }
  }
  out.vx = out.mom_x.cwiseQuotient(out.rho);
  out.vy = out.mom_y.cwiseQuotient(out.rho);

  if (req.convective) {
    for (const auto& c : req.components) out.convective[c] = Eigen::VectorXd::Zero(nn);
    for (std::size_t a = 0; a < ps.size(); ++a) {
      const auto& w_x = x_weights.at(ps.x[a]);
      const auto& w_y = y_weights.at(ps.y[a]);
      const double v[2] = {ps.vx[a], ps.vy[a]};
      for (const auto& [j, wy] : w_y)
        for (const auto& [i, wx] : w_x) {
          const int n = mesh.index(i, j);
          const double dv[2] = {out.vx[n] - v[0], out.vy[n] - v[1]};
          for (auto& [c, field] : out.convective) {
            const auto [r, s] = component_index(c);
            field[n] -= ps.mass[a] * dv[r] * dv[s] * wx * wy;  // (2.12)
          }
        }
    }
  }

  if (req.interaction) {
    std::vector<std::pair<int, int>> comps;
    for (const auto& c : req.components) comps.push_back(component_index(c));
    for (std::size_t a = 0; a < comps.size(); ++a)
      for (std::size_t b = 0; b < a; ++b)
        if (comps[a] == comps[b]) throw ConfigError("", "tensor component '" + req.components[a] + "' requested twice");
    const int nc = static_cast<int>(comps.size());
    std::vector<std::vector<double>> acc(omp_get_max_threads(), std::vector<double>(nn * nc, 0.0));
#pragma omp parallel
    {
      auto& buf = acc[omp_get_thread_num()];
      BondWeights w;
#pragma omp for schedule(dynamic, 256)
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        const auto& pf = pairs[p];
        double tab[4];
        for (int c = 0; c < nc; ++c) tab[c] = pf.f[comps[c].first] * pf.d[comps[c].second];
        w.clear();
        append_bond_weights(kernel, mesh, Vec2(ps.x[pf.j], ps.y[pf.j]), pf.d, w);
        for (const auto& [n, b] : w)
          for (int c = 0; c < nc; ++c) buf[n * nc + c] += tab[c] * b;  // (2.13)
      }
    }
    for (int c = 0; c < nc; ++c) {
      Eigen::VectorXd field = Eigen::VectorXd::Zero(nn);
      for (const auto& buf : acc)
        for (int n = 0; n < nn; ++n) field[n] += buf[n * nc + c];
      out.interaction[req.components[c]] = field;
    }
  }
  return out;
}

}  // namespace closurelab
