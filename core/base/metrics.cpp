#include "core/base/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace closurelab {

namespace {
// Sums of squares are exact enough, and cannot overflow or lose every digit to underflow, while every term is
// below 2^480 and the total above 2^-900 (or zero because every term is zero).
constexpr double safe_top = 0x1p480, safe_bottom = 0x1p-450;

// ‖d‖₂ / ‖r‖₂ (or ‖d‖₂ when r = 0) from the plain sums `num` = Σd², `den` = Σr², redone scaled by the largest
// magnitude `top` when a plain sum may have overflowed or underflowed.
template <class Visit>
double relative_l2(double num, double den, double top, const Visit& visit) {
  if (!std::isfinite(top)) return std::numeric_limits<double>::quiet_NaN();
  const bool safe = top < safe_top && (top == 0 || top > safe_bottom);
  if (!safe) {
    num = 0.0;
    den = 0.0;
    visit([&](double d, double r) {
      num += (d / top) * (d / top);
      den += (r / top) * (r / top);
    });
  }
  // A vanishing reference has no relative error: NaN (JSON null) unless the difference vanishes too, never the
  // absolute ‖d‖₂ read as a relative one.
  return den > 0 ? std::sqrt(num / den) : num == 0 ? 0.0 : std::numeric_limits<double>::quiet_NaN();
}

// A norm relative to an unusable scale is no result: both norms NaN (JSON null).
void mark_unusable_scale(ErrorNorms& e, double scale) {
  if (usable_scale(scale)) return;
  e.max_rel = std::numeric_limits<double>::quiet_NaN();
  e.l2_rel = std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

bool usable_scale(double scale) { return std::isfinite(scale) && scale > 0; }

double robust_norm(const Eigen::VectorXd& v) {
  const double n = v.norm();
  if (std::isfinite(n) && (n > safe_bottom || (n == 0 && v.isZero(0)))) return n;
  if (!v.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  return v.stableNorm();
}

json ErrorNorms::to_json() const {
  if (count == 0) return {{"max_rel", nullptr}, {"l2_rel", nullptr}, {"count", 0}};  // an empty subset has no error
  const auto value = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"max_rel", value(max_rel)}, {"l2_rel", value(l2_rel)}, {"count", count}};
}

ErrorNorms error_norms(const Eigen::VectorXd& u, const Eigen::VectorXd& ref, const std::vector<bool>& mask,
                       double scale) {
  ErrorNorms e;
  double num = 0.0, den = 0.0, top = 0.0;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    if (!mask[k]) continue;
    const double d = u[k] - ref[k];
    e.max_rel = std::max(e.max_rel, std::abs(d));
    top = std::max({top, std::abs(d), std::abs(ref[k])});
    if (!std::isfinite(d) || !std::isfinite(ref[k])) top = std::numeric_limits<double>::infinity();
    num += d * d;
    den += ref[k] * ref[k];
    ++e.count;
  }
  if (top == std::numeric_limits<double>::infinity()) e.max_rel = std::numeric_limits<double>::quiet_NaN();
  e.max_rel /= scale;
  e.l2_rel = relative_l2(num, den, top, [&](const auto& add) {
    for (Eigen::Index k = 0; k < u.size(); ++k)
      if (mask[k]) add(u[k] - ref[k], ref[k]);
  });
  mark_unusable_scale(e, scale);
  return e;
}

ErrorNorms vector_error_norms(const Eigen::VectorXd& ux, const Eigen::VectorXd& uy, const Eigen::VectorXd& rx,
                              const Eigen::VectorXd& ry, double scale) {
  ErrorNorms e;
  double num = 0.0, den = 0.0, top = 0.0;
  for (Eigen::Index k = 0; k < ux.size(); ++k) {
    const double dx = ux[k] - rx[k], dy = uy[k] - ry[k];
    top = std::max({top, std::abs(dx), std::abs(dy), std::abs(rx[k]), std::abs(ry[k])});
    if (!std::isfinite(dx) || !std::isfinite(dy) || !std::isfinite(rx[k]) || !std::isfinite(ry[k]))
      top = std::numeric_limits<double>::infinity();
    const double d2 = dx * dx + dy * dy;
    e.max_rel = std::max(e.max_rel, d2);
    num += d2;
    den += rx[k] * rx[k] + ry[k] * ry[k];
    ++e.count;
  }
  const bool safe = top < safe_top && (top == 0 || top > safe_bottom);
  if (!std::isfinite(top)) {
    e.max_rel = std::numeric_limits<double>::quiet_NaN();
  } else if (!safe) {  // the largest Euclidean difference, scaled
    double m = 0.0;
    for (Eigen::Index k = 0; k < ux.size(); ++k) m = std::max(m, std::hypot(ux[k] - rx[k], uy[k] - ry[k]));
    e.max_rel = m;
  } else {
    e.max_rel = std::sqrt(e.max_rel);
  }
  e.max_rel /= scale;
  e.l2_rel = relative_l2(num, den, top, [&](const auto& add) {
    for (Eigen::Index k = 0; k < ux.size(); ++k) {
      add(ux[k] - rx[k], rx[k]);
      add(uy[k] - ry[k], ry[k]);
    }
  });
  mark_unusable_scale(e, scale);
  return e;
}

json node_error_summary(const Eigen::VectorXd& a, const Eigen::VectorXd& ref, const std::vector<bool>& mask,
                        double scale) {
  double mx = 0.0, s2 = 0.0, r2 = 0.0, top = 0.0;
  int n = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!mask[k]) continue;
    const double d = a[k] - ref[k];
    mx = std::max(mx, std::abs(d));
    top = std::max({top, std::abs(d), std::abs(ref[k])});
    if (!std::isfinite(d) || !std::isfinite(ref[k])) top = std::numeric_limits<double>::infinity();
    s2 += d * d;
    r2 += ref[k] * ref[k];
    ++n;
  }
  if (!std::isfinite(top)) mx = std::numeric_limits<double>::quiet_NaN();
  double l2 = relative_l2(s2, r2, top, [&](const auto& add) {
    for (Eigen::Index k = 0; k < a.size(); ++k)
      if (mask[k]) add(a[k] - ref[k], ref[k]);
  });
  // A vanishing reference keeps its documented 0 (finite data only).
  const bool ref_vanishes = std::isfinite(top) && [&] {
    for (Eigen::Index k = 0; k < a.size(); ++k)
      if (mask[k] && ref[k] != 0) return false;
    return true;
  }();
  if (ref_vanishes) l2 = 0.0;
  return {{"max_rel", mx / scale}, {"l2_rel", l2}, {"nodes", n}};
}

Eigen::VectorXd vector_magnitudes(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  Eigen::VectorXd m(x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) m[k] = std::hypot(x[k], y[k]);
  return m;
}

double peak_relative_difference(const Eigen::VectorXd& u, const Eigen::VectorXd& ref) {
  const double peak = ref.maxCoeff();
  if (!usable_scale(peak)) return std::numeric_limits<double>::quiet_NaN();  // no peak to be relative to
  return (u.maxCoeff() - peak) / peak;
}

}  // namespace closurelab
