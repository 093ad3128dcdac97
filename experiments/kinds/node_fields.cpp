#include "experiments/kinds/node_fields.hpp"

#include <algorithm>

#include "core/base/metrics.hpp"

namespace closurelab {

namespace {

Eigen::VectorXd where(const Eigen::VectorXd& v, const std::vector<bool>& mask, bool value) {
  std::vector<int> picked;
  for (std::size_t n = 0; n < mask.size(); ++n)
    if (mask[n] == value) picked.push_back(static_cast<int>(n));
  return v(picked);
}

}  // namespace

Eigen::VectorXd speed(const NodeVelocity& f) { return vector_magnitudes(f.x, f.y); }

json field_json(const NodeVelocity& f) { return {{"vx", f.x}, {"vy", f.y}}; }

NodeVelocity scaled(const NodeVelocity& f, double a) { return NodeVelocity{a * f.x, a * f.y}; }

double fitted(const NodeVelocity& f, const NodeVelocity& unit) {
  return (f.x.dot(unit.x) + f.y.dot(unit.y)) / (unit.x.squaredNorm() + unit.y.squaredNorm());
}

json norms(const NodeVelocity& u, const NodeVelocity& ref, double scale, const std::vector<int>& interior,
           const std::vector<bool>& outside_solid) {
  const json all = vector_error_norms(u.x, u.y, ref.x, ref.y, scale).to_json();
  json out = {{"all_nodes", all}, {"fluid_nodes", all}, {"peak_relative_difference", peak_relative_difference(speed(u), speed(ref))}};
  const auto part = [&](bool outside) {
    return vector_error_norms(where(u.x, outside_solid, outside), where(u.y, outside_solid, outside),
                              where(ref.x, outside_solid, outside), where(ref.y, outside_solid, outside), scale)
        .to_json();
  };
  if (!outside_solid.empty()) {
    out["fluid_nodes"] = part(true);
    if (std::find(outside_solid.begin(), outside_solid.end(), false) != outside_solid.end())
      out["solid_nodes"] = part(false);
  }
  if (!interior.empty()) {
    const auto pick = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(v(interior)); };
    out["interior_nodes"] = vector_error_norms(pick(u.x), pick(u.y), pick(ref.x), pick(ref.y), scale).to_json();
  }
  return out;
}

}  // namespace closurelab
