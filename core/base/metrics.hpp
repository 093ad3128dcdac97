#pragma once
// Error norms for comparing a solution with a reference, over a subset of points. Every norm is computed
// without overflow or underflow: the plain sum of squares where it is safe (bit for bit as before), else the
// same sum scaled by the largest magnitude (finite data of 1e200 gives a finite relative error, not 0 or NaN).
#include <Eigen/Core>
#include <vector>

#include "core/base/params.hpp"

namespace closurelab {

struct ErrorNorms {
  double max_rel = 0.0;  // max |u − ref| / scale
  double l2_rel = 0.0;   // ‖u − ref‖₂ / ‖ref‖₂ over the subset
  int count = 0;
  json to_json() const;
};

// Norms over the points where mask is true. `scale` normalizes the max error (e.g. the reference's peak
// over the whole channel, so that near-wall points with tiny reference values do not blow up). A scale that is
// zero, negative or not finite (a reference at rest, or one whose peak overflowed) is not usable: both norms are
// then NaN (JSON null), never the absolute error read as a relative one, and the caller marks its row
// (usable_scale). Likewise l2_rel is NaN where the reference vanishes on the subset and the difference does not.
ErrorNorms error_norms(const Eigen::VectorXd& u, const Eigen::VectorXd& ref, const std::vector<bool>& mask,
                       double scale);

// The same for a vector field (u_x, u_y) against (r_x, r_y) at every point: max |u − r| (Euclidean) / scale and
// ‖u − r‖₂ / ‖r‖₂ over both components.
ErrorNorms vector_error_norms(const Eigen::VectorXd& ux, const Eigen::VectorXd& uy, const Eigen::VectorXd& rx,
                              const Eigen::VectorXd& ry, double scale);

// The stress tables' summary (App. C, snapshot closure): {"max_rel": max|a − ref| / scale, "l2_rel":
// ‖a − ref‖₂ / ‖ref‖₂ (0 when ref vanishes), "nodes": the count}, over the nodes where mask is true.
json node_error_summary(const Eigen::VectorXd& a, const Eigen::VectorXd& ref, const std::vector<bool>& mask,
                        double scale);

// A scale that a relative error may be divided by: finite and positive.
bool usable_scale(double scale);

// |(x_k, y_k)| by std::hypot: the speeds of a vector field without overflow (1e160 squared is inf) or underflow.
Eigen::VectorXd vector_magnitudes(const Eigen::VectorXd& x, const Eigen::VectorXd& y);

// ‖v‖₂ without overflow or underflow: v.norm() when its sum of squares is safely in range (the common case,
// bit for bit), else Eigen's scaled stableNorm(). Non-finite entries give a non-finite norm.
double robust_norm(const Eigen::VectorXd& v);

// The paper's §7 metric: relative difference of the peak values, (max u − max ref) / max ref (NaN where max ref
// is not a usable scale).
double peak_relative_difference(const Eigen::VectorXd& u, const Eigen::VectorXd& ref);

}  // namespace closurelab
