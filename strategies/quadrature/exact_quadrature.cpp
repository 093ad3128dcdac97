#include "strategies/quadrature/exact_quadrature.hpp"

#include <omp.h>

#include <chrono>
#include <stdexcept>

#include "core/base/errors.hpp"
#include "strategies/quadrature/bond_weights.hpp"

namespace closurelab {

void ExactQuadrature::setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
                            const std::vector<std::string>& components) {
  const auto t0 = std::chrono::steady_clock::now();
  check_mesh_matches_box(nodes, scene.box);
  comp_index_ = component_indices(components);
  components_ = components;
  node_count_ = nodes.size();
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

  // Bond weights per pair, in parallel blocks, then concatenated in pair order.
  const std::size_t np = pairs.size();
  const int nthreads = omp_get_max_threads();
  std::vector<std::vector<std::int32_t>> block_node(nthreads);
  std::vector<std::vector<double>> block_value(nthreads);
  std::vector<std::int64_t> count(np, 0);
#pragma omp parallel num_threads(nthreads)
  {
    const int t = omp_get_thread_num();
    BondWeights w;
#pragma omp for schedule(static)
    for (std::size_t p = 0; p < np; ++p) {
      w.clear();
      const Vec2 qj(ps_.x[pairs[p].j], ps_.y[pairs[p].j]);
      append_bond_weights(kernel, nodes, qj, pairs[p].d, w);
      count[p] = static_cast<std::int64_t>(w.size());
      for (const auto& [n, b] : w) {
        block_node[t].push_back(n);
        block_value[t].push_back(b);
      }
    }
  }
  // schedule(static) gives each thread one contiguous, ordered block of pairs.
  weight_start_.assign(np + 1, 0);
  for (std::size_t p = 0; p < np; ++p) weight_start_[p + 1] = weight_start_[p] + count[p];
  weight_node_.clear();
  weight_value_.clear();
  weight_node_.reserve(weight_start_[np]);
  weight_value_.reserve(weight_start_[np]);
  for (int t = 0; t < nthreads; ++t) {
    weight_node_.insert(weight_node_.end(), block_node[t].begin(), block_node[t].end());
    weight_value_.insert(weight_value_.end(), block_value[t].begin(), block_value[t].end());
  }
  if (static_cast<std::int64_t>(weight_node_.size()) != weight_start_[np])
    throw std::logic_error("exact quadrature: bond weights out of order");
  cost_ = QuadratureCost{};
  cost_.bond_weights = weight_start_[np];
  cost_.sample_points = static_cast<long>(moving_points_.size());
  cost_.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::map<std::string, Eigen::VectorXd> ExactQuadrature::evaluate(const VelocitySampler& sampler) {
  if (!engine_) throw std::logic_error("exact quadrature: evaluate before setup");
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Matrix2Xd v = sampler(moving_points_);
  if (v.cols() != static_cast<Eigen::Index>(moving_.size()))
    throw NumericalError("exact quadrature: the velocity sampler returned the wrong number of points");
  for (std::size_t k = 0; k < moving_.size(); ++k) {
    ps_.vx[moving_[k]] = require_finite(v(0, k), "sampled velocity");
    ps_.vy[moving_[k]] = require_finite(v(1, k), "sampled velocity");
  }
  const std::vector<PairForce> pairs = engine_->pair_forces();  // (5.1) at the sampled velocities
  if (pairs.size() != pair_count()) throw std::logic_error("exact quadrature: the pair set changed since setup");

  const int nc = static_cast<int>(comp_index_.size());
  const int nthreads = omp_get_max_threads();
  std::vector<std::vector<double>> acc(nthreads, std::vector<double>(static_cast<std::size_t>(node_count_) * nc, 0.0));
#pragma omp parallel num_threads(nthreads)
  {
    auto& buf = acc[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      double tab[4];
      for (int c = 0; c < nc; ++c) tab[c] = pairs[p].f[comp_index_[c].first] * pairs[p].d[comp_index_[c].second];
      for (std::int64_t e = weight_start_[p]; e < weight_start_[p + 1]; ++e) {
        double* out = &buf[static_cast<std::size_t>(weight_node_[e]) * nc];
        const double b = weight_value_[e];
        for (int c = 0; c < nc; ++c) out[c] += tab[c] * b;  // (2.13)
      }
    }
  }
  auto out = reduce_node_buffers(acc, node_count_, components_);
  ++cost_.evaluations;
  cost_.pair_forces += static_cast<long>(pairs.size());
  cost_.evaluate_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace closurelab
