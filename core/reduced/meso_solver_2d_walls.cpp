// The 2D reduced model's walled box (the lid-driven cavity): its checks, the face difference of either box and the
// terms the walls add to the incompressible rate (core/reduced/walled_box_2d.hpp).
#include <string>

#include "core/base/errors.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/reduced/walled_box_2d.hpp"

namespace closurelab {

void check_walled_meso_2d(const TensorMesh2D& coarse, const MesoSolver2DOptions& o) {
  if (o.equations != CoarseEquations::incompressible)
    throw ConfigError("/solver/equations",
                      "a walled box (the cavity) takes the incompressible equations (its walls' "
                      "constraint forces and no-flux projection); got " +
                          name_of(o.equations));
  if (o.discretization != Discretization::coarse_fine)
    throw ConfigError(
        "/closure/discretization",
        "a walled box (the cavity) solves for the fluid particles' velocities on their lattice, the walls' "
        "known velocities as data: use coarse_fine; got " +
            name_of(o.discretization));
  if (coarse.nx() > kMaxWalledProjectionSide || coarse.ny() > kMaxWalledProjectionSide)
    throw ConfigError("/solver/spacing_over_eta", "the walled projection is dense and takes at most " +
                                                      std::to_string(kMaxWalledProjectionSide) + " cells along a side");
}

Eigen::VectorXd MesoSolver2D::face_diff(const Eigen::VectorXd& on_faces, int axis) const {
  return walls_ ? walled_face_difference(coarse_, on_faces, axis, opt_.divergence_order)
                : face_difference(coarse_, on_faces, axis, opt_.divergence_order);
}

bool MesoSolver2D::add_wall_terms(bool convective, bool stress, FaceStress& t, Eigen::VectorXd& cx, Eigen::VectorXd& cy,
                                  std::string& issue) {
  if (convective) {  // the fluid's momentum flux Q on the faces (the walls' particles carry none)
    const FluidConvectiveFlux::OnFaces q = walls_->convective.evaluate(t.rx, t.ry);
    t.txx -= q.xx;
    t.tyx -= q.yx;
    t.txy -= q.xy;
    t.tyy -= q.yy;
  }
  if (!stress) return true;
  return walls_->constraint.evaluate(closure_sampler(t.rx, t.ry), cx, cy, issue);
}

}  // namespace closurelab
