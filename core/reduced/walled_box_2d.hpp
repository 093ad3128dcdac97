#pragma once
// The 2D reduced model in a walled rectangle (the lid-driven cavity; core/reduced/meso_solver_2d.hpp, equations
// incompressible): the pieces its walls need, each an exact statement about the particles on their lattice.
//   - The coarse nodes are cell-centred over the fluid's rectangle (continuum_mesh_for); the x-faces (T_xx, T_yx)
//     are the n_x + 1 lines x = x_0 + iΔ, the two outermost on the wall surfaces, likewise the y-faces.
//   - Deconvolution data: the average (2.9) at node i mixes the fluid with the wall particles at their prescribed
//     velocities, v̄_i = Σ_all ψ_ia v_a / Σ_all ψ_ia. With every particle on the lattice (mass ρ0 ε'²) the fluid's
//     part is exact and linear in the fluid velocities, s_i v̄_i − w_i = Σ_fluid ε'² ψ(x_i − q_f) V_f = (A V)_i,
//     s_i = ε'² Σ_all ψ_ia, w_i = ε'² Σ_walls ψ_iw v_w, A the coarse–fine Kronecker operator on the fluid lattice:
//     the walls' known velocities are data, not unknowns.
//   - The walls' constraint forces (DESIGN.md §6): the wall particles are held by forces the stress divergence
//     does not contain, so the fluid's averaged momentum balance is div T_int + F_c with
//     F_c(x) = −Σ_walls ψ(x − q_w) f_w, f_w the pair forces (5.1) on wall particle w (the pairs T_int sums).
//   - The convective flux of the fluid alone, Q(x) = Σ_fluid m ψ(x − q_f) V_f ⊗ V_f, evaluated on the faces (the
//     walls' particles do not travel, so they carry no momentum flux): ∂_t Σ_fluid m ψ V = … − div Q, exactly.
//   - The discrete projection for the model's divergence with no flow through the walls: D v = face difference of
//     the velocity interpolated to the faces (zero normal velocity on the wall faces; order 4 inside, order 2 next
//     to a wall), and Π = I − Dᵀ (D Dᵀ)⁺ D, dense (the coarse mesh is small; refused beyond 64 × 64 cells). It
//     projects the rate, not the state: the state starts as the average of the initial particles, the lid's part
//     included (at rest, v̄ = w/s, not zero: the window of a node next to the lid holds lid particles at U), and
//     that part's normal component on the side walls' faces near the lid is not zero (starting from v̄ = 0 instead
//     left the lid's share out of every later v̄: 18.8 % against 9.5 % at n = 50).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/mesh.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

class SphEngine;
struct ParticleSystem;

// The faces of a walled cell-centred mesh along `axis` (0: x-faces, n_x + 1 per row; 1: y-faces), not periodic.
TensorMesh2D walled_faces_of(const TensorMesh2D& cells, int axis);
// ∂_x (axis 0) or ∂_y (axis 1) at the cell centres of a field on the walled faces of that axis: order 2, or order 4
// ([27 (T_{i+½} − T_{i−½}) − (T_{i+3/2} − T_{i−3/2})] / 24Δ) where its stencil stays inside, order 2 next to a wall.
Eigen::VectorXd walled_face_difference(const TensorMesh2D& cells, const Eigen::VectorXd& on_faces, int axis, int order);
// The centre values interpolated to the walled faces of `axis` (order 4 where the stencil stays inside, order 2
// next to a wall), zero on the wall faces: the normal velocity the projection's divergence reads.
Eigen::VectorXd walled_to_faces(const TensorMesh2D& cells, const Eigen::VectorXd& at_centres, int axis, int order);
// The largest mesh the dense projection takes (cells along a side).
inline constexpr int kMaxWalledProjectionSide = 64;

class WalledProjection2D {
 public:
  // ConfigError at /solver/spacing_over_eta beyond kMaxWalledProjectionSide cells along a side.
  WalledProjection2D(const TensorMesh2D& cells, int order);
  // D v: the discrete divergence at the cell centres.
  Eigen::VectorXd divergence(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) const;
  void project(Eigen::VectorXd& vx, Eigen::VectorXd& vy) const;  // v ← Π v

 private:
  TensorMesh2D cells_;
  int order_;
  Eigen::MatrixXd dt_;    // Dᵀ (2n × n)
  Eigen::MatrixXd pinv_;  // (D Dᵀ)⁺ (n × n), eigenvalues below 1e-12 of the largest dropped
};

// The walls' part of the averaging at the coarse nodes and the fluid lattice the closure solves on.
struct WalledAveraging {
  TensorMesh2D fluid_lattice;      // the fluid particles' sites (cell-centred over the fluid's rectangle)
  Eigen::VectorXd scale;           // s_i = ε'² Σ_all ψ_ia
  Eigen::VectorXd wall_x, wall_y;  // w_i = ε'² Σ_walls ψ_iw v_w
  // The fluid data (A V) of averaged velocities v̄ at the nodes: s ∘ v̄ − w.
  Eigen::VectorXd fluid_data(const Eigen::VectorXd& v, int component) const;
};
WalledAveraging walled_averaging(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& coarse);

// The fluid's convective flux Q on the walled faces from the fluid particles' velocities on the fluid lattice:
// xx and yx on the x-faces, xy and yy on the y-faces (Q_ab = ρ0 A_face(V_a V_b), A_face the lattice-to-face
// Kronecker operator with weights ε'² ψ).
class FluidConvectiveFlux {
 public:
  FluidConvectiveFlux(const AveragingKernel& kernel, const TensorMesh2D& coarse, const TensorMesh2D& fluid_lattice,
                      double rho0);
  struct OnFaces {
    Eigen::VectorXd xx, yx, xy, yy;
  };
  OnFaces evaluate(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) const;

 private:
  ForwardOperator to_x_faces_, to_y_faces_;
  double rho0_;
};

// F_c at the coarse nodes for fluid velocities given by a sampler (wall particles at their prescribed velocities):
// one pair-force sweep of the lattice per call.
class WallConstraintForces2D {
 public:
  WallConstraintForces2D(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& coarse);
  ~WallConstraintForces2D();
  // Both components at the nodes; false (message in `issue`) on a non-finite sample.
  bool evaluate(const VelocitySampler& v, Eigen::VectorXd& fx, Eigen::VectorXd& fy, std::string& issue);
  long pair_forces() const { return pair_forces_; }  // over all calls

 private:
  std::unique_ptr<Scene> scene_;  // owned copy: the engine keeps a reference
  std::unique_ptr<ParticleSystem> ps_;
  std::unique_ptr<SphEngine> engine_;
  std::vector<std::int32_t> moving_;
  std::vector<Vec2> moving_points_;
  std::vector<std::int32_t> wall_column_;  // per particle: its column of `weights_` (−1: not a wall in reach)
  Eigen::SparseMatrix<double, Eigen::RowMajor> weights_;  // nodes × walls in reach: ψ(x_i − q_w)
  long pair_forces_ = 0;
};

// The four together, as the 2D reduced model holds them in a walled box.
struct WalledBox2D {
  WalledBox2D(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& coarse, int divergence_order)
      : averaging(walled_averaging(scene, kernel, coarse)),
        convective(kernel, coarse, averaging.fluid_lattice, scene.rho0),
        projection(coarse, divergence_order),
        constraint(scene, kernel, coarse) {}
  WalledAveraging averaging;
  FluidConvectiveFlux convective;
  WalledProjection2D projection;
  WallConstraintForces2D constraint;
};

}  // namespace closurelab
