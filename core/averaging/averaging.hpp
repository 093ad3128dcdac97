#pragma once
// The averaging operators: from a particle snapshot onto mesh nodes, with the window ψ_η of an
// AveragingKernel and periodic images — density (2.8), velocity (2.9), convective stress (2.12),
// interaction stress (2.13, via the bond integral) and external force (2.14). Only what is requested is
// computed; tensor components are named "xx", "xy", "yx", "yy" with T_ab = Σ f_a d_b (d = q_k − q_j).
#include <Eigen/Core>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/particles.hpp"
#include "core/sph/sph_engine.hpp"

namespace closurelab {

struct AveragingRequest {
  bool convective = false;                       // (2.12)
  bool interaction = false;                      // (2.13): needs the pair forces
  bool external = false;                         // (2.14): needs the body force
  std::vector<std::string> components{"xy"};     // tensor components of the stresses
};

struct MesoFields {
  Eigen::VectorXd rho, mom_x, mom_y, vx, vy;  // (2.8), (2.9) and v̄ = ρv̄ / ρ̄
  std::map<std::string, Eigen::VectorXd> convective, interaction;
  Eigen::VectorXd fx, fy;  // (2.14)
};

// `pairs` (for the interaction stress) and `force_x` (body force per unit mass along x, acting on the
// particles that are not held fixed) are needed only when requested.
MesoFields average_particles(const ParticleSystem& ps, const PeriodicBox& box, const AveragingKernel& kernel,
                             const TensorMesh2D& mesh, const AveragingRequest& request,
                             const std::vector<PairForce>& pairs = {},
                             const std::function<double(double)>& force_x = {});

// The mesh on which x-invariant scenes are averaged: one column at x = 0 (periodic in x with the box
// length) and rows of the given spacing over [0, ly].
TensorMesh2D column_mesh(const PeriodicBox& box, double spacing);

// (row, column) of a tensor component name.
std::pair<int, int> component_index(const std::string& name);

}  // namespace closurelab
