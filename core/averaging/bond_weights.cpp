#include "core/averaging/bond_weights.hpp"

#include <algorithm>
#include <cmath>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"

namespace closurelab {

namespace {

void add_entry(BondWeights& out, std::size_t first, int node, double w) {
  for (std::size_t e = first; e < out.size(); ++e)
    if (out[e].first == node) return void(out[e].second += w);
  out.emplace_back(node, w);
}

}  // namespace

void append_bond_weights(const AveragingKernel& kernel, const TensorMesh2D& mesh, const Vec2& qj, const Vec2& d,
                         BondWeights& out) {
  const std::size_t first = out.size();
  const Vec2 mid = qj + 0.5 * d;
  const double reach = kernel.support_radius() + 0.5 * d.norm();
  for_nodes_within(mesh.y, mid.y(), reach, [&](int jy, double oy) {
    for_nodes_within(mesh.x, mid.x(), reach, [&](int ix, double ox) {
      const Vec2 node = mesh.node(ix, jy);
      const Vec2 shift = node - Vec2(ox, oy) - mid;  // the periodic image shift
      const double b = kernel.bond_integral(node, qj + shift, qj + shift + d);  // (A.1)
      if (b != 0.0) add_entry(out, first, mesh.index(ix, jy), b);
    });
  });
}

void append_bond_weights_x_integrated(const AveragingKernel& kernel, const TensorMesh2D& mesh, double qj_y, double d_y,
                                      BondWeights& out) {
  const std::size_t first = out.size();
  const double mid = qj_y + 0.5 * d_y;
  const double reach = kernel.support_radius() + 0.5 * std::abs(d_y);
  const double phi0 = kernel.factor(0.0);
  for_nodes_within(mesh.y, mid, reach, [&](int jy, double oy) {
    // ∫ φ(x-part) dR_x = 1 for every s, so the x-integrated weight is the 1D bond integral of φ along y:
    // the 2D bond integral of a bond along y through the node's column, divided by φ(0).
    const double shift = mesh.y.node(jy) - oy - mid;
    const Vec2 a(0.0, qj_y + shift), node(0.0, mesh.y.node(jy));
    const double b = kernel.bond_integral(node, a, a + Vec2(0.0, d_y)) / phi0;
    if (b == 0.0) return;
    for (int ix = 0; ix < mesh.nx(); ++ix) add_entry(out, first, mesh.index(ix, jy), b);
  });
}

void check_mesh_matches_box(const TensorMesh2D& mesh, const PeriodicBox& box) {
  const auto check = [](const UniformMesh1D& a, bool periodic, double length, const char* name) {
    if (a.periodic != periodic || (a.periodic && std::abs(a.period - length) > 1e-12 * length))
      throw ConfigError("", std::string("node mesh ") + name + "-axis periodicity does not match the scene's box");
  };
  check(mesh.x, box.periodic_x, box.lx, "x");
  check(mesh.y, box.periodic_y, box.ly, "y");
}

std::vector<std::pair<int, int>> component_indices(const std::vector<std::string>& components) {
  if (components.empty()) throw ConfigError("", "no stress components requested");
  std::vector<std::pair<int, int>> out;
  for (const auto& c : components) out.push_back(component_index(c));
  return out;
}

std::map<std::string, Eigen::VectorXd> reduce_node_buffers(const std::vector<std::vector<double>>& buffers,
                                                           int node_count, const std::vector<std::string>& components) {
  const int nc = static_cast<int>(components.size());
  std::map<std::string, Eigen::VectorXd> out;
  for (int c = 0; c < nc; ++c) {
    Eigen::VectorXd field = Eigen::VectorXd::Zero(node_count);
    for (const auto& buf : buffers)
      for (int n = 0; n < node_count; ++n) field[n] += buf[static_cast<std::size_t>(n) * nc + c];
    out[components[c]] = field;
  }
  return out;
}

}  // namespace closurelab
