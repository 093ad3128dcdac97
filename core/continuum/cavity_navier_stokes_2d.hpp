#pragma once
// The coarse continuum baseline inside walls: the incompressible Navier–Stokes equations
//   ∂_t v + ∇·(v ⊗ v) = −∇p/ρ + ν Δv,   ∇·v = 0,
// in the rectangle covered by a cell-centred mesh, no slip on its four sides, the top side sliding along x at the lid
// speed U (the lid-driven cavity). A textbook staggered (MAC) discretization (Harlow & Welch 1965; the central
// variant of Griebel, Dornseifer & Neunhoeffer, "Numerical Simulation in Fluid Dynamics", SIAM 1998, ch. 3):
//  - unknowns: v_x on the vertical faces (i h_x, (j+½) h_y), v_y on the horizontal faces ((i+½) h_x, j h_y), the
//    pressure at the cell centres (the mesh's nodes). The normal velocity on a wall face is zero; a tangential
//    velocity half a cell outside a wall is the ghost 2 v_wall − v_inside, so that the linear interpolation across the
//    wall gives v_wall on it.
//  - space: the convective flux divergence ∇·(v ⊗ v) in conservative form, the products of central averages at the
//    cell centres (normal fluxes) and cell corners (cross fluxes); the 5-point Laplacian. Second order in the interior.
//  - time: Adams–Bashforth 2 for convection and diffusion together, then the exact discrete projection
//    v ← v* − Δt G φ, D G φ = D v* / Δt (D the face-to-centre divergence, G its negative adjoint on the interior faces:
//    the Neumann 5-point Laplacian), solved by a sparse LDLᵀ factorization (Eigen's SimplicialLDLT) computed once,
//    φ pinned at cell 0 (the system is consistent: the walls' normal velocities are zero). After it D v is zero to
//    round-off. Step Δt = min(cfl h_min / max(|v|, U), viscous_number h_min² / ν), as the periodic baseline.
//  - nodes: the velocity at a cell centre is the mean of its two faces.
// Checked at Re = 100 (tests/numerical/test_cavity_navier_stokes_2d.cpp): the centre lines self-converge at second
// order and lie within the error of Ghia, Ghia & Shin's (1982) table of them.
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <string>

#include "core/continuum/continuum_navier_stokes_2d.hpp"

namespace closurelab {

class CavityNavierStokes2D : public ContinuumNavierStokes2D {
 public:
  // mesh: cell-centred, periodic in neither direction, at least 4 cells along a side (the walls are the mesh's outer
  // cell faces); density ρ > 0, dynamic viscosity μ > 0, lid speed U (the top wall's velocity along x).
  // std::invalid_argument otherwise.
  CavityNavierStokes2D(TensorMesh2D mesh, double density, double viscosity, double lid_speed,
                       CoarseNavierStokes2DOptions options = {});

  std::string method() const override {
    return "staggered (MAC) central differences, AB2, exact sparse projection (LDLT), no-slip walls and a sliding lid";
  }
  double set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) override;
  bool step(double dt) override;
  double time_step() const override;
  const TensorMesh2D& mesh() const override { return mesh_; }
  const Eigen::VectorXd& vx() const override { return cx_; }
  const Eigen::VectorXd& vy() const override { return cy_; }
  Eigen::VectorXd divergence() const override;

  // The velocity at (x, y) inside the walls (mesh coordinates): each component interpolated bilinearly from its
  // faces, the ghost values beyond a wall making it the wall's velocity on the wall; the wall velocity outside.
  Eigen::Vector2d velocity_at(double x, double y) const override;
  // The pressure of the last projection, ρ φ (φ zero at cell 0); zero before the first step.
  const Eigen::VectorXd& pressure() const { return p_; }

 private:
  // v_x at face (i, j), i = 0..nx, j = −1..ny (ghosts beyond the bottom and top walls); v_y at face (i, j),
  // i = −1..nx (ghosts beyond the side walls), j = 0..ny.
  double u_at(const Eigen::VectorXd& u, int i, int j) const;
  double v_at(const Eigen::VectorXd& v, int i, int j) const;
  void rate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& ru, Eigen::VectorXd& rv) const;
  // Removes the gradient part of (u, v); the pressure ρ φ / dt when dt > 0.
  void project(Eigen::VectorXd& u, Eigen::VectorXd& v, double dt);
  Eigen::VectorXd face_divergence(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const;
  void update_nodes();

  TensorMesh2D mesh_;
  int nx_, ny_;
  double hx_, hy_, rho_, nu_, lid_;
  CoarseNavierStokes2DOptions opt_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> poisson_;  // −D G on cells 1..N−1
  Eigen::VectorXd u_, v_, cx_, cy_, p_, ru_prev_, rv_prev_;
  double dt_prev_ = 0.0;
};

}  // namespace closurelab
