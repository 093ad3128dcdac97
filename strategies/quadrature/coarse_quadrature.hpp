#pragma once
// The coarse stress quadrature (5.27): the interaction stress written as an integral over bond midpoints R
// and bond vectors ρ (5.25), with R on a coarse grid of N_C nodes and ρ over the fine lattice offsets of
// the SPH support (|ρ_j| < support):
//   T_int(x) ≈ ½ Σ_β (N/N_C) Σ_j f(q_β − ρ_j/2, q_β + ρ_j/2) ⊗ ρ_j ∫₀¹ ψ_η(s(x − q_β − ρ_j/2) + (1 − s)(x − q_β + ρ_j/2)) ds,
// with f the pair force (5.1) (core/sph/sph_pair_force.hpp) on the virtual particle at q_β − ρ_j/2 due to the
// one at q_β + ρ_j/2 (the convention of (2.13): f on j due to k, tensor with q_k − q_j), velocities from the
// sampler, the constant number density n* and pressure P* of §5.2 and the viscosity at each end.
// Prefactor: f̄ of (5.24) is the pair force times the pair density n*², and dx' dx'' = dR dρ; the lattice
// ρ-sum has cells |Ω|/N = 1/n*, the R-sum cells |Ω|/N_C, so (|Ω|/N_C)(|Ω|/N) n*² = N/N_C.
//
// The R-grid is cell-centred: the lattice is tiled by blocks of s_x × s_y sites (N/N_C = s_x s_y), whose
// centres c_β are the paper's q_β; the virtual pair of (β, ρ_j) runs from c_β to c_β + ρ_j, so the pairs
// of ±ρ_j have their midpoints symmetric about c_β (a midpoint rule, 2nd order where the integrand is
// smooth). With strides 1 the c_β are the lattice sites, the virtual pairs are the lattice's ordered pairs
// (each unordered pair twice, hence ½) and (5.27) is (2.13) exactly. For even strides c_β lies between
// sites and the velocities are sampled there. Pairs with both ends in a wall are skipped, as in direct SPH.
//
// Walls: the integrand of (5.25) jumps where a bond straddles a wall surface (fluid velocity on one end, a
// particle at rest on the other), so a coarse R-row there aliases the jump (errors of several % at the
// paper's N/N_C = 16, see results/paper/appendix_c). Option refine_walls: R-rows within one SPH support of
// a wall surface are kept at lattice resolution (a composite Riemann sum; O(support/ε') extra rows, still
// independent of N).
//
// x-invariant scenes (a periodic strip): with stride_x = 0 the R-grid is one column per strip period and
// the R_x-integral of the bond weight is done exactly: ∫ dR_x ∫₀¹ ψ ds = ∫₀¹ φ(y − a_y − s ρ_y) ds, since the
// velocities do not depend on x. This is the x-Riemann sum in its limit of infinitely many columns (which
// the strip's n_x columns already reach to round-off), so N/N_C = n_x s_y and the cost is independent of
// the strip's width: O(N_C J) with J ≈ π (support/ε')² offsets, independent of N.
//
// Doubly periodic scenes without walls, of one phase, whose R-grid is the node mesh (stride_x ε' and stride_y ε'
// the node spacings, one R-cell per node: the 2D reduced model's face meshes): the weight of the virtual pair
// (β, ρ_j) at node x is that of (0, ρ_j) at x − c_β, so (5.27) is, for each offset j, a cyclic convolution over
// the R-grid of the pair forces with one bond-weight stencil W_j. Both rows of T are real, so one complex
// transform per offset serves them: T_xb + i T_yb = F⁻¹[Σ_j ρ_j,b Ŵ_j F(f_x,j + i f_y,j)]. Setup tabulates the J
// stencils (J × the window's nodes weights instead of N_C times as many); a call costs J + 2 FFTs of N_C points,
// independent of N and of the window's width. The same sums as the table, to round-off (tested). Chosen by
// setup wherever it applies (convolves()); the constructor's `convolution = false` keeps the table (tests, bench).
#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/sph/scene.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/averaging/bond_weights.hpp"

namespace closurelab {

class CoarseQuadrature : public StressQuadrature {
 public:
  // stride_x = 0: x-integrated (x-invariant scenes only); else strides in lattice spacings, dividing n_x, n_y.
  // refine_walls: R-rows within one SPH support of a wall at full resolution (see above). convolution: the
  // periodic FFT convolution where it applies (see above); false: always the bond-weight table.
  CoarseQuadrature(int stride_x, int stride_y, bool refine_walls = false, bool convolution = true);
  ~CoarseQuadrature() override;
  std::string name() const override { return "coarse"; }
  void check(const Scene& scene, const TensorMesh2D& nodes, const std::vector<std::string>& components) const override;
  void setup(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& nodes,
             const std::vector<std::string>& components) override;
  QuadratureResult evaluate(const VelocitySampler& v) override;
  QuadratureCost setup_cost() const override { return cost_; }

  // The coarse total virial Σ_(β,j) ½ (N/N_C) f ⊗ ρ_j: the integral of T_int over a periodic domain.
  Eigen::Matrix2d virial(const VelocitySampler& v) const;
  double coarsening() const { return coarsening_; }  // N/N_C
  int r_nodes() const { return r_nodes_; }            // N_C
  int offsets() const { return offsets_; }            // J
  std::size_t virtual_pairs() const { return pairs_.size(); }
  bool convolves() const { return convolution_ != nullptr; }  // setup chose the periodic convolution

 private:
  struct VirtualPair {
    std::int32_t sa, sb;  // sample indices of the two ends (−1: a wall site, at rest)
    Vec2 rho;             // ρ = q_b − q_a
    double F;             // w'(|ρ|)/|ρ|
    double mu_ab;         // μ_ab of (5.1): pair_viscosity of the two ends' phases (core/sph/sph_pair_force.hpp)
    double p_over_n2;     // P*/n*² of each end, plus the unlike-pair excess of (7.1) when the phases differ
    double weight;  // ½ (N/N_C share) per unit bond integral (x-integrated: per unit 1D bond integral)
    double mass;    // ½ × the particles the base site stands for (its share of the virial)
    double beta;  // ghost-velocity walls (a fluid–wall pair): v_a − v_b = ±β v_fluid as in direct SPH; else 0
  };
  struct Run {
    int centre, sites;  // centre in half lattice units; the lattice sites it stands for
  };
  struct RGrid {
    std::vector<Run> cols, rows;
  };
  RGrid r_grid(const Scene& scene) const;
  void set_pair_physics(const Scene& scene, int ha, int hb, const Vec2& qa, const Vec2& qb, VirtualPair& p) const;
  Eigen::Matrix2Xd sample(const VelocitySampler& v) const;
  Vec2 pair_force(const VirtualPair& p, const Eigen::Matrix2Xd& v) const;
  // Whether the periodic convolution applies to these pairs (ordered R-row, R-column, offset) on `nodes`.
  bool translation_invariant(const Scene& scene, const TensorMesh2D& nodes, const RGrid& grid) const;
  std::map<std::string, Eigen::VectorXd> convolve(const Eigen::Matrix2Xd& v);

  int stride_x_, stride_y_;
  bool refine_walls_, use_convolution_;
  bool set_up_ = false;
  int r_nodes_ = 0, offsets_ = 0;
  double coarsening_ = 0.0;  // N/N_C
  double p_over_n2_ = 0.0, n_star_ = 0.0;
  std::vector<Vec2> points_;
  std::vector<VirtualPair> pairs_;
  std::vector<std::string> components_;
  BondWeightTable weights_;  // by virtual pair; the weights include ½ N/N_C (empty when convolving)
  struct Convolution;        // the stencils' transforms and the FFT (periodic convolution)
  std::unique_ptr<Convolution> convolution_;
  QuadratureCost cost_;
};

}  // namespace closurelab
