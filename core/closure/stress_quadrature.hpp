#pragma once
// The stress-quadrature strategy family (DESIGN.md §2): the interaction stress T_int on mesh nodes from the
// particle velocities that the closure reconstructs, exactly by the pair sum (2.13) or by the coarse
// quadrature (5.27). Particle positions are kept intact (incompressible flow, §5.2), so all geometry
// (bonds, bond integrals) is set up once; `evaluate` only needs the velocity field.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/base/mesh.hpp"
#include "core/base/params.hpp"

namespace closurelab {

class AveragingKernel;
struct Scene;

// The closure's velocity field: v at any points, as a 2 x n matrix (row 0: v_x, row 1: v_y). Points inside
// walls must come back at rest (the sampler is responsible: the quadrature asks for lattice points and for
// the coarse quadrature's offsets alike).
using VelocitySampler = std::function<Eigen::Matrix2Xd(const std::vector<Vec2>& points)>;

struct QuadratureCost {
  long evaluations = 0;        // calls of evaluate()
  long pair_forces = 0;        // pair-force evaluations, all calls
  long bond_weights = 0;       // precomputed bond-integral weights (node, bond) — set up once
  long sample_points = 0;      // velocity samples requested per call
  double setup_seconds = 0.0;
  double evaluate_seconds = 0.0;  // all calls
  json to_json() const;
};

class StressQuadrature {
 public:
  virtual ~StressQuadrature() = default;
  virtual std::string name() const = 0;
  // Binds to the scene's lattice and SPH model, the averaging kernel, the nodes where T_int is wanted and
  // the tensor components ("xx", "xy", "yx", "yy"; T_ab = Σ f_a d_b as in core/averaging.hpp).
  // Throws ConfigError when the configuration does not fit the scene (e.g. N/N_C not dividing the lattice).
  virtual void setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
                     const std::vector<std::string>& components) = 0;
  // T_int at the nodes, per requested component, for the velocity field `v`.
  virtual std::map<std::string, Eigen::VectorXd> evaluate(const VelocitySampler& v) = 0;
  virtual QuadratureCost cost() const = 0;
};

}  // namespace closurelab
