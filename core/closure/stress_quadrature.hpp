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
#include "core/base/status.hpp"

namespace closurelab {

class AveragingKernel;
struct Scene;

// The closure's velocity field: v at any points, as a 2 x n matrix (row 0: v_x, row 1: v_y). Points inside
// walls must come back at rest (the sampler is responsible: the quadrature asks for lattice points and for
// the coarse quadrature's offsets alike).
using VelocitySampler = std::function<Eigen::Matrix2Xd(const std::vector<Vec2>& points)>;

// One evaluation's outcome, as a deconvolution's (core/closure/deconvolver.hpp): a value with a status and this
// call's cost. A non-finite sampled velocity or stress is a numerical issue (message says which), not an
// exception; misuse (evaluate before setup, a sampler returning the wrong number of points) is a logic error.
struct QuadratureResult {
  std::map<std::string, Eigen::VectorXd> stress;  // T_int per requested component at the nodes
  Status status = Status::converged;
  std::string message;
  long pair_forces = 0;  // pair-force evaluations of this call
  double seconds = 0.0;
};

// What a quadrature costs: the setup facts (from setup_cost()) and, summed by the caller with add(), its calls.
struct QuadratureCost {
  long evaluations = 0;        // calls of evaluate()
  long pair_forces = 0;        // pair-force evaluations, all calls
  long bond_weights = 0;       // precomputed bond-integral weights (node, bond) — set up once
  long sample_points = 0;      // velocity samples requested per call
  double setup_seconds = 0.0;
  double evaluate_seconds = 0.0;  // all calls
  void add(const QuadratureResult& call) {
    ++evaluations;
    pair_forces += call.pair_forces;
    evaluate_seconds += call.seconds;
  }
  json to_json() const;
};

// `r` itself, or marked a numerical issue when a stress component is not finite.
QuadratureResult finite_or_issue(QuadratureResult r, const std::string& who);

class StressQuadrature {
 public:
  virtual ~StressQuadrature() = default;
  virtual std::string name() const = 0;
  // The checks setup() starts with, without its work (validation of a spec): ConfigError when the
  // configuration does not fit the scene, the nodes or the components.
  virtual void check(const Scene& scene, const TensorMesh2D& nodes, const std::vector<std::string>& components) const = 0;
  // Binds to the scene's lattice and SPH model, the averaging kernel, the nodes where T_int is wanted and
  // the tensor components ("xx", "xy", "yx", "yy"; T_ab = Σ f_a d_b as in core/averaging/averaging.hpp).
  // Throws ConfigError when the configuration does not fit the scene (e.g. N/N_C not dividing the lattice).
  virtual void setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
                     const std::vector<std::string>& components) = 0;
  // T_int at the nodes, per requested component, for the velocity field `v`.
  virtual QuadratureResult evaluate(const VelocitySampler& v) = 0;
  // The setup's cost (bond weights, sample points, seconds); evaluations are counted by the caller.
  virtual QuadratureCost setup_cost() const = 0;
};

}  // namespace closurelab
