#pragma once
// The coarse continuum baseline's common face ("what a user would pick instead"): an incompressible
// Navier–Stokes solver stepped on a coarse mesh of cell-centred nodes, whatever its boundaries. Two solvers:
//   CoarseNavierStokes2D  doubly periodic, collocated, FFT projection (core/continuum/coarse_navier_stokes_2d.hpp);
//   CavityNavierStokes2D  a rectangle inside no-slip walls, the top one sliding, staggered (MAC) grid
//                         (core/continuum/cavity_navier_stokes_2d.hpp).
// continuum_baseline_for picks the one a scene needs, on the mesh continuum_mesh_for lays.
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>

#include "core/base/mesh.hpp"

namespace closurelab {

struct Scene;
class AveragingKernel;

struct CoarseNavierStokes2DOptions {
  double cfl = 0.5;               // Δt ≤ cfl · h_min / max|v| (central convection with AB2: keep it ≤ 0.5)
  double viscous_number = 0.125;  // Δt ≤ viscous_number · h_min² / ν (≤ 1/8: AB2's diffusion limit in 2D)
  double max_time_step = std::numeric_limits<double>::infinity();
};

class ContinuumNavierStokes2D {
 public:
  virtual ~ContinuumNavierStokes2D() = default;

  // What the row calls the method (discretization, time stepping, projection).
  virtual std::string method() const = 0;
  // Sets the velocity at the nodes (time 0, the AB2 history cleared) and projects it onto the discretely
  // divergence-free fields; returns the max-node magnitude of what the projection removed.
  virtual double set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) = 0;
  // One step of length dt followed by the projection. False (and the state unchanged) if the result is not finite.
  virtual bool step(double dt) = 0;
  virtual double time_step() const = 0;  // the CFL and viscous limits at the current velocity
  virtual const TensorMesh2D& mesh() const = 0;
  virtual const Eigen::VectorXd& vx() const = 0;  // at the nodes (flat j · nx + i)
  virtual const Eigen::VectorXd& vy() const = 0;
  // The solver's own discrete divergence of the current velocity, one value per node.
  virtual Eigen::VectorXd divergence() const = 0;
  // The velocity at a point of the scene (mesh coordinates), interpolated from the solver's unknowns; outside the
  // fluid (in a wall) the wall's velocity.
  virtual Eigen::Vector2d velocity_at(double x, double y) const = 0;

  // Steps to time t (the last steps shortened to land on it); false on a non-finite state.
  bool advance_to(double t);
  double time() const { return time_; }
  long steps() const { return steps_; }

 protected:
  // The variable-step Adams–Bashforth 2 update v + Δt [(1 + ω/2) r − (ω/2) r_prev], ω = Δt / Δt_prev; forward
  // Euler when dt_prev is 0 (no history).
  static Eigen::VectorXd ab2(const Eigen::VectorXd& v, const Eigen::VectorXd& r, const Eigen::VectorXd& r_prev,
                             double dt, double dt_prev);
  double time_ = 0.0;
  long steps_ = 0;
};

// The mesh the baseline steps on: the 2D reduced model's doubly periodic mesh (coarse_mesh_2d) for a periodic
// scene; for the lid-driven cavity the cell-centred mesh over the fluid's square with the spacing nearest
// spacing_over_eta · η' that divides its side (at least 4 cells). ConfigError (path relative to the cell) where
// neither fits.
TensorMesh2D continuum_mesh_for(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta);
// The baseline for a scene on that mesh: ρ0, the one phase's viscosity, the body force (averaged with
// `average_force` where given, else sampled at the nodes; periodic scenes only) and the lid speed of a cavity.
// std::invalid_argument for a scene neither solver serves.
std::unique_ptr<ContinuumNavierStokes2D> continuum_baseline_for(const Scene& scene, const TensorMesh2D& mesh,
                                                                CoarseNavierStokes2DOptions options = {},
                                                                const AveragingKernel* average_force = nullptr);

}  // namespace closurelab
