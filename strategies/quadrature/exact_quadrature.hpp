#pragma once
// The exact stress quadrature: the pair sum (2.13) over every interacting particle pair of the scene's
// lattice, T_int(x) = Σ_(j,k) f_jk ⊗ (q_k − q_j) ∫₀¹ ψ_η(s(x − q_k) + (1 − s)(x − q_j)) ds, with periodic
// images as in core/averaging/averaging.cpp. Positions are intact (§5.2): setup finds the pairs once and tabulates
// the (node, pair) bond weights (sparse, CSR by pair); evaluate puts the sampled velocities on the
// particles (held particles at rest), takes the pair forces (5.1) from the direct SPH engine (so wall
// models, densities and pressures are those of direct SPH) and forms the weighted sum: O(N) per call.
#include <memory>

#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/averaging/bond_weights.hpp"

namespace closurelab {

class ExactQuadrature : public StressQuadrature {
 public:
  std::string name() const override { return "exact"; }
  void check(const Scene& scene, const TensorMesh2D& nodes, const std::vector<std::string>& components) const override;
  void setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
             const std::vector<std::string>& components) override;
  QuadratureResult evaluate(const VelocitySampler& v) override;
  QuadratureCost setup_cost() const override { return cost_; }

  std::size_t pair_count() const { return weights_.bonds(); }
  std::size_t particle_count() const { return ps_.size(); }

 private:
  std::unique_ptr<Scene> scene_;  // owned copy: the engine keeps a reference
  ParticleSystem ps_;
  std::unique_ptr<SphEngine> engine_;
  std::vector<std::int32_t> moving_;  // particles whose velocity comes from the sampler
  std::vector<Vec2> moving_points_;
  BondWeightTable weights_;  // by pair, in the engine's pair order
  QuadratureCost cost_;
};

}  // namespace closurelab
