#include "core/sph/sph_kernel.hpp"

#include <cmath>

#include "core/base/errors.hpp"

namespace closurelab {

SmoothingKernel::SmoothingKernel(Type type, double h) : type_(type), h_(h) {
  if (!(h > 0)) throw ConfigError("/h_over_dx", "smoothing length must be positive");
  if (type == Type::quintic) {
    support_ = 3.0 * h;
    sigma_ = 7.0 / (478.0 * M_PI * h * h);
  } else {
    support_ = 2.0 * h;
    sigma_ = 7.0 / (4.0 * M_PI * h * h);
  }
  inv_h_ = 1.0 / h;
  sigma_over_h_ = sigma_ / h;
  sigma_over_h2_ = sigma_ / (h * h);
}

double SmoothingKernel::w(double r) const {
  const double q = r / h_;
  if (type_ == Type::quintic) {
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q, b = 2.0 - q, c = 1.0 - q;
    double s = a * a * a * a * a;
    if (q < 2.0) s -= 6.0 * b * b * b * b * b;
    if (q < 1.0) s += 15.0 * c * c * c * c * c;
    return sigma_ * s;
  }
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  return sigma_ * t * t * t * t * (2.0 * q + 1.0);
}

double SmoothingKernel::dw(double r) const {
  const double q = r / h_;
  if (type_ == Type::quintic) {
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q, b = 2.0 - q, c = 1.0 - q;
    double s = -5.0 * a * a * a * a;
    if (q < 2.0) s += 30.0 * b * b * b * b;
    if (q < 1.0) s -= 75.0 * c * c * c * c;
    return sigma_ * s / h_;
  }
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  return sigma_ * (-5.0 * q) * t * t * t / h_;
}

}  // namespace closurelab
