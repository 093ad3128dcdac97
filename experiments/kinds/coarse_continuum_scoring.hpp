#pragma once
// How the coarse continuum baseline is scored (kind coarse_continuum_2d, experiments/kinds/coarse_continuum.cpp): on
// the mode of a scene with an exact single-mode solution (the Taylor–Green vortex, the cellular flow), and on a scene
// with walls and no exact field (the lid-driven cavity) through the averaging, by Ghia's centre lines and against the
// same solver on a finer mesh.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/params.hpp"
#include "core/continuum/continuum_navier_stokes_2d.hpp"
#include "core/sph/scene.hpp"
#include "experiments/kinds/node_fields.hpp"

namespace closurelab {

// The scene's mode at unit amplitude at the nodes: the Taylor–Green vortex (−cos kx sin ky, sin kx cos ky) or the
// cellular mode (sin kx cos ky, −cos kx sin ky); the exact velocity at time t is mode_amplitude(t) times it.
NodeVelocity mode_shape(const Scene& s, const TensorMesh2D& mesh);
double mode_amplitude(const Scene& s, double t);
double mode_wavenumber(const Scene& s);
// The cavity's nodes at least 3η' from every wall (Scene::in_interior's distance); none for other scenes.
std::vector<int> interior_nodes(const Scene& s, const TensorMesh2D& mesh);

// The baseline seen through the averaging, as the direct SPH is seen: the scene's own particles (the fluid on its
// lattice carrying the baseline's velocity_at their sites, the walls their prescribed velocity) averaged by the
// kernel onto the mesh ((2.9), average_particles). Near a wall the window then mixes the fluid with the wall's
// particles exactly as it does for the averaged direct SPH.
NodeVelocity averaged_baseline(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh,
                               const ContinuumNavierStokes2D& baseline);

// A replay of a baseline run (the same solver, started as the timed one was, deterministic) for what the timed runs
// leave out: the averaged view onto `onto` at each of `times` up to `target` (in order) and at `target`, and, for a
// cavity at a Reynolds number Ghia tabulates, the centre lines at `target` against Ghia, Ghia & Shin (1982) as the
// direct validation reports them (u at x = L/2, v at y = L/2 at his points; max_abs_u, max_abs_v and worst over the
// points inside the cavity, in units of the lid speed). False if the replay leaves the finite numbers.
struct BaselineViews {
  std::vector<NodeVelocity> at_times;
  NodeVelocity at_target;
  json centrelines;  // null without a Ghia table
};
bool replay_baseline_views(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& onto,
                           ContinuumNavierStokes2D& baseline, const std::vector<double>& times, double target,
                           BaselineViews& out);

// A scene without an exact field (the cavity), its baseline started at rest: replays of the baseline on `mesh` and of
// the same solver on a mesh kFineContinuumRefinement times finer over the same rectangle (the stand-in for the exact
// field: at refinement 8 of the cavity's 16 × 16 it is within ~1e-3 U of the converged solution,
// tests/numerical/test_cavity_navier_stokes_2d.cpp, so the averaged direct SPH's distance from its averaged view is
// the reference's own error, and the coarse baseline's distance from it the coarse mesh's). Their views go to
// `coarse` and `fine`; `fields` gains averaged_baseline and averaged_fine_continuum at `target`; `errors` gains
// centrelines and fine_continuum_centrelines (with a Ghia table) and averaged_baseline_vs_averaged_fine_continuum
// (norms relative to `scale`, interior nodes apart). False (nothing written) if a replay fails.
constexpr int kFineContinuumRefinement = 8;
// The worst max_rel over a transient's saved times (its array of snapshots) per region (all_nodes, interior_nodes) of
// each comparison of a scene without an exact field: baseline_vs_averaged_direct_sph,
// averaged_baseline_vs_averaged_direct_sph, direct_sph_vs_averaged_fine_continuum (an empty object where none).
json worst_over_saved_times(const json& transient);
bool walled_views(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh,
                  CoarseNavierStokes2DOptions options, const std::vector<double>& times, double target, double scale,
                  BaselineViews& coarse, BaselineViews& fine, json& fields, json& errors);

}  // namespace closurelab
