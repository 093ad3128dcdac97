#pragma once
// The coarse velocity at the nodes of a 2D mesh and how the 2D kinds score it, one copy for the reduced models
// (mesh_2d, force_density_2d) and the coarse continuum baseline: the field, its row JSON, its speed, its amplitude
// on a mode, and its error norms over all nodes and by region (fluid and solid nodes, the interior nodes).
#include <Eigen/Core>
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {

struct NodeVelocity {
  Eigen::VectorXd x, y;  // at the mesh's nodes (flat j · nx + i)
};

// |v| at each node, by hypot: a speed of 1e160 squared overflows (it made the scale infinite and every max_rel 0).
Eigen::VectorXd speed(const NodeVelocity& f);
// The row's form of a field: {"vx": [...], "vy": [...]}.
json field_json(const NodeVelocity& f);
NodeVelocity scaled(const NodeVelocity& f, double a);
// The least-squares amplitude of `f` relative to `unit`: Σ f · unit / Σ |unit|².
double fitted(const NodeVelocity& f, const NodeVelocity& unit);
// The error of `u` against `ref`, max |u − r| / scale and ‖u − r‖₂ / ‖r‖₂ (vector_error_norms), over all nodes (the
// headline), with the relative difference of their peak speeds (the paper's metric). By region: with
// `outside_solid` (a flag per node), "fluid_nodes" over the nodes outside the solid and "solid_nodes" over those
// inside (where there are any); without it "fluid_nodes" is all nodes. With `interior` (node indices),
// "interior_nodes" over those.
json norms(const NodeVelocity& u, const NodeVelocity& ref, double scale, const std::vector<int>& interior = {},
           const std::vector<bool>& outside_solid = {});

}  // namespace closurelab
