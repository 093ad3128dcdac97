#include "core/base/metrics.hpp"

#include <algorithm>
#include <cmath>

namespace closurelab {

json ErrorNorms::to_json() const {
  if (count == 0) return {{"max_rel", nullptr}, {"l2_rel", nullptr}, {"count", 0}};  // an empty subset has no error
  return {{"max_rel", max_rel}, {"l2_rel", l2_rel}, {"count", count}};
}

ErrorNorms error_norms(const Eigen::VectorXd& u, const Eigen::VectorXd& ref, const std::vector<bool>& mask,
                       double scale) {
  ErrorNorms e;
  double num = 0.0, den = 0.0;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    if (!mask[k]) continue;
    const double d = u[k] - ref[k];
    e.max_rel = std::max(e.max_rel, std::abs(d));
    num += d * d;
    den += ref[k] * ref[k];
    ++e.count;
  }
  e.max_rel = scale > 0 ? e.max_rel / scale : e.max_rel;
  e.l2_rel = den > 0 ? std::sqrt(num / den) : std::sqrt(num);
  return e;
}

ErrorNorms vector_error_norms(const Eigen::VectorXd& ux, const Eigen::VectorXd& uy, const Eigen::VectorXd& rx,
                              const Eigen::VectorXd& ry, double scale) {
  ErrorNorms e;
  double num = 0.0, den = 0.0;
  for (Eigen::Index k = 0; k < ux.size(); ++k) {
    const double d2 = (ux[k] - rx[k]) * (ux[k] - rx[k]) + (uy[k] - ry[k]) * (uy[k] - ry[k]);
    e.max_rel = std::max(e.max_rel, d2);
    num += d2;
    den += rx[k] * rx[k] + ry[k] * ry[k];
    ++e.count;
  }
  e.max_rel = scale > 0 ? std::sqrt(e.max_rel) / scale : std::sqrt(e.max_rel);
  e.l2_rel = den > 0 ? std::sqrt(num / den) : std::sqrt(num);
  return e;
}

json node_error_summary(const Eigen::VectorXd& a, const Eigen::VectorXd& ref, const std::vector<bool>& mask,
                        double scale) {
  double mx = 0.0, s2 = 0.0, r2 = 0.0;
  int n = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!mask[k]) continue;
    mx = std::max(mx, std::abs(a[k] - ref[k]));
    s2 += (a[k] - ref[k]) * (a[k] - ref[k]);
    r2 += ref[k] * ref[k];
    ++n;
  }
  return {{"max_rel", mx / scale}, {"l2_rel", r2 > 0 ? std::sqrt(s2 / r2) : 0.0}, {"nodes", n}};
}

double peak_relative_difference(const Eigen::VectorXd& u, const Eigen::VectorXd& ref) {
  return (u.maxCoeff() - ref.maxCoeff()) / ref.maxCoeff();
}

}  // namespace closurelab
