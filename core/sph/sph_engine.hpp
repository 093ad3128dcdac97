#pragma once
// The direct SPH model: Newton's equations (2.1)–(2.3) with the pair force (5.1), Morris's viscous term
// with the pair viscosity μ_ij (μ_i + μ_j, or the harmonic mean for unlike particles), the scene's equation of
// state (weakly compressible, or van der Waals (7.1) with k_ij per pair), zero-velocity (5.3) or
// ghost-velocity walls, and a body force. Symmetric pair evaluation over a Verlet pair list (cell-list search
// with a skin), grouped by particle into rows and blocks (sph_pair_passes.hpp), OpenMP over blocks with per-thread
// accumulators. Only the particles a scene needs are stepped: wall particles farther than the interaction range
// from every fluid particle take no part.
// The density pass computes the kernel values of a block of listed pairs in one vectorized loop (w and w'/r from
// r², SmoothingKernel::w_and_dw_over_r, without branches; compiled for AVX-512, AVX2 and the baseline on x86-64,
// same bits, PairKernelIsa), then adds them row by row; the force pass sums each row's force on its particle in registers.
// List pairs beyond the support contribute zero instead of being skipped; the reciprocals 1/n are taken once per
// particle; only the fluid–wall pairs of ghost-velocity walls take the general path (their ghost velocity).
// With SphEngineOptions::formulation = transport_velocity the force pass and the step are instead those of the
// transport-velocity formulation (core/sph/transport_velocity.hpp: PySPH's TVFScheme); the density pass is shared.
#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "core/base/enum_names.hpp"
#include "core/base/mesh.hpp"
#include "core/sph/neighbour_search.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/transport_velocity.hpp"

namespace closurelab {

// One interacting pair for the interaction stress (2.13): bond d = q_k − q_j (minimum image) and the
// force f on particle j due to particle k.
struct PairForce {
  std::int32_t j, k;
  Vec2 d, f;
};

// What the force pass reads of a particle, in one place (one cache-line half per particle).
struct SphPairInput {
  double p_over_n2, inv_n, vx, vy;
};

// The instruction set of the density pass's kernel loop: the widest of AVX-512 (eight pairs per vector) and AVX2
// (four) that the CPU has where an x86-64 baseline build runs, else the build's own. All compute the same bits (no
// fused multiply-add); tests compare them.
enum class PairKernelIsa { baseline, avx2, avx512 };

template <>
struct EnumNames<PairKernelIsa> {
  static constexpr std::array<std::pair<PairKernelIsa, std::string_view>, 3> table{
      {{PairKernelIsa::baseline, "baseline"}, {PairKernelIsa::avx2, "avx2"}, {PairKernelIsa::avx512, "avx512"}}};
};

bool pair_kernel_isa_available(PairKernelIsa isa);
PairKernelIsa pair_kernel_isa();
// For tests and benchmarks: every engine's next density pass uses `isa`; std::invalid_argument where it is not
// available.
void set_pair_kernel_isa(PairKernelIsa isa);

struct PairBlocks;  // the list's rows and blocks, as the pair passes read them (sph_pair_passes.hpp)

class SphEngine {
 public:
  // Refuses (std::invalid_argument) the transport-velocity formulation on a scene with ghost-velocity walls: that
  // formulation's fixed particles (walls, solids) take the generalized wall condition (transport_velocity.hpp).
  SphEngine(const Scene& scene, ParticleSystem& particles, const SphEngineOptions& options = {});

  // Number densities and accelerations at the current positions and velocities.
  void compute_accelerations();
  // One velocity-Verlet step (kick–drift–kick; the second force evaluation uses the predicted velocity,
  // since the viscous force depends on velocities). One force evaluation per step. Under the transport-velocity
  // formulation, its step instead (transport_velocity.hpp: PySPH's TransportVelocityStep in PEC mode).
  void step(double dt);
  // (5.21)–(5.22) with Δ = ε': κ min(ε' / (c + max|v|), ρ ε'² / (μ_max β)). The signal speed of a weakly
  // compressible model is the sound speed plus the flow speed; β is the ghost-velocity wall's stiffening of
  // the fluid–wall viscous coupling (1 for zero-velocity walls), without which κ = 0.25 is unstable.
  // Transport velocity: κ min(h / (c + U), ρ0 h² / (2 μ_max)), U the larger of the scene's analytic peak and
  // max|v| (PySPH's taylor_green.py at κ = 0.25: 0.25 h/(c0 + U) and 0.125 h²/ν, a fixed step).
  double time_step(double kappa) const;

  // Pair forces at the current state (densities recomputed), for the averaging operators.
  std::vector<PairForce> pair_forces();

  const std::vector<double>& number_density() const { return n_; }
  const std::vector<double>& ax() const { return ax_; }
  const std::vector<double>& ay() const { return ay_; }
  const std::vector<std::int32_t>& moving() const { return moving_; }
  std::int64_t pair_evaluations() const { return pair_evaluations_; }
  SphFormulation formulation() const { return options_.formulation; }
  // Transport velocity only: ṽ and the background pressure's acceleration â − a of the last evaluation
  // (empty under the standard formulation).
  const std::vector<double>& transport_vx() const { return tvx_; }
  const std::vector<double>& transport_vy() const { return tvy_; }
  const std::vector<double>& background_ax() const { return bx_; }
  const std::vector<double>& background_ay() const { return by_; }
  std::int64_t list_rebuilds() const { return list_rebuilds_; }
  std::size_t pair_count() const { return list_.pairs.size(); }
  std::size_t active_count() const { return active_.size(); }  // moving particles and the walls they reach
  double max_speed() const;

 private:
  void rebuild_pairs_if_needed();
  PairBlocks blocks() const;
  void compute_density();
  // Thread t's share of the force pass (the rows of blocks nb·t/nt to nb·(t+1)/nt) into its accumulator.
  void force_rows_of_thread(std::size_t t, std::size_t nt);
  double pressure(std::int32_t a) const;
  // (5.1) for pair p = (i, j) of the list at the current densities, given the like-pair P/n² of its particles.
  Vec2 pair_force(std::int32_t i, std::int32_t j, std::size_t p, double p_over_n2_i, double p_over_n2_j) const;
  // Relative velocity used by the viscous term of pair (a, b) (ghost velocities for fluid–wall pairs).
  Vec2 relative_velocity(std::int32_t a, std::int32_t b) const;
  // Transport velocity: the per-particle inputs of its pair pass at the current densities (ṽ = v at the first
  // call), its force pass and step.
  void prepare_transport_inputs();
  // The generalized wall condition: each wall particle's extrapolated pressure, density and ghost velocity from its
  // fluid neighbours (transport_velocity.hpp), into its tvf_input_.
  void apply_transport_wall_condition();
  void compute_transport_accelerations();
  void transport_step(double dt);

  const Scene& scene_;
  ParticleSystem& ps_;
  SphEngineOptions options_;
  bool transport_ = false;          // options_.formulation == transport_velocity
  double transport_eps_ = 0.0;      // ε = 0.01 h² of the viscous term
  double background_pressure_ = 0.0;  // p_b
  std::vector<TvfParticle> tvf_input_;
  std::vector<double> stress_weight_;  // transport velocity with walls: 1 for a moving particle, 0 for a fixed one
  std::vector<std::size_t> wall_pairs_;  // the listed fluid–wall pairs (transport velocity with fixed particles)
  bool transport_walls_ = false;         // transport velocity and some fixed particle
  // The wall condition's sums over a wall particle's fluid neighbours: Σ W, Σ v W, Σ p W, Σ ρ x_wf W.
  std::vector<double> wall_sum_w_, wall_sum_vx_, wall_sum_vy_, wall_sum_p_, wall_sum_rx_, wall_sum_ry_;
  std::vector<double> tvx_, tvy_, bx_, by_;
  SmoothingKernel w_;
  double skin_, mass_, viscous_stiffening_ = 1.0;
  double unlike_excess_ = 0.0;  // added to P/n² of both particles of an unlike pair ((7.1) with k*)
  std::vector<std::int32_t> active_, moving_;
  std::vector<double> n_static_;  // wall–wall part of wall densities (constant: walls do not move)
  std::vector<double> n_, ax_, ay_, x_built_, y_built_;
  std::vector<double> mu_, vhx_, vhy_;
  std::vector<SphPairInput> pair_input_;
  bool one_phase_ = true;  // every particle of one phase: μ_ij = 2μ and no unlike-pair excess
  double inv_lx_ = 0.0, inv_ly_ = 0.0;
  GroupedPairList list_;                             // the Verlet list, grouped by the first particle
  std::vector<double> pair_dx_, pair_dy_, pair_f_;   // minimum-image q_i − q_j and w'(r)/r per listed pair
  std::vector<std::vector<double>> thread_scratch_;  // a block's per-pair kernel values, per thread
  std::vector<std::vector<double>> thread_buf_;
  std::int64_t pair_evaluations_ = 0, list_rebuilds_ = 0;
  bool built_ = false;
};

}  // namespace closurelab
