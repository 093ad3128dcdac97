#include "strategies/quadrature/exact_quadrature.hpp"

#include <omp.h>

#include <chrono>
#include <stdexcept>

#include "core/base/errors.hpp"
#include "core/averaging/bond_weights.hpp"

namespace closurelab {

void ExactQuadrature::check(const Scene& scene, const TensorMesh2D& nodes,
                            const std::vector<std::string>& components) const {
  check_mesh_matches_box(nodes, scene.box);
  component_indices(components);
}

void ExactQuadrature::setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
                            const std::vector<std::string>& components) {
  const auto t0 = std::chrono::steady_clock::now();
  check(scene, nodes, components);
  scene_ = std::make_unique<Scene>(scene);
  ps_ = scene_->make_particles();
  moving_.clear();
  moving_points_.clear();
  for (std::size_t a = 0; a < ps_.size(); ++a)
    if (!ps_.fixed[a]) {
      moving_.push_back(static_cast<std::int32_t>(a));
      moving_points_.emplace_back(ps_.x[a], ps_.y[a]);
    }
  engine_ = std::make_unique<SphEngine>(*scene_, ps_);
  const std::vector<PairForce> pairs = engine_->pair_forces();  // geometry only: velocities are zero here

  weights_.tabulate(pairs.size(), nodes.size(), components, [&](std::size_t p, BondWeights& w) {
    append_bond_weights(kernel, nodes, Vec2(ps_.x[pairs[p].j], ps_.y[pairs[p].j]), pairs[p].d, w);
  });
  cost_ = QuadratureCost{};
  cost_.bond_weights = weights_.entries();
  cost_.sample_points = static_cast<long>(moving_points_.size());
  cost_.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

QuadratureResult ExactQuadrature::evaluate(const VelocitySampler& sampler) {
  if (!engine_) throw std::logic_error("exact quadrature: evaluate before setup");
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Matrix2Xd v = sampler(moving_points_);
  if (v.cols() != static_cast<Eigen::Index>(moving_.size()))
    throw std::logic_error("exact quadrature: the velocity sampler returned the wrong number of points");
  QuadratureResult r;
  if (!v.allFinite()) {
    r.status = Status::numerical_issue;
    r.message = "exact quadrature: non-finite sampled velocity";
    return r;
  }
  for (std::size_t k = 0; k < moving_.size(); ++k) {
    ps_.vx[moving_[k]] = v(0, k);
    ps_.vy[moving_[k]] = v(1, k);
  }
  const std::vector<PairForce> pairs = engine_->pair_forces();  // (5.1) at the sampled velocities
  if (pairs.size() != pair_count()) throw std::logic_error("exact quadrature: the pair set changed since setup");

  r.stress = weights_.accumulate([&](std::size_t p) { return std::make_pair(pairs[p].f, pairs[p].d); });
  r.pair_forces = static_cast<long>(pairs.size());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finite_or_issue(std::move(r), "exact quadrature");
}

}  // namespace closurelab
