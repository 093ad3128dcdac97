#pragma once
// SPH smoothing functions w_ε of (5.1)–(5.2) in 2D: the quintic spline (support 3h, Morris et al. 1997)
// and Wendland C2 (support 2h). Both normalized, ∫ w = 1.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include "core/base/enum_names.hpp"

namespace closurelab {

class SmoothingKernel {
 public:
  enum class Type { quintic, wendland_c2 };
  SmoothingKernel(Type type, double h);

  double h() const { return h_; }
  double support() const { return support_; }
  Type type() const { return type_; }
  // w(r) and dw/dr at distance r >= 0.
  double w(double r) const;
  double dw(double r) const;
  // For the pair loops: w(r) and w'(r)/r from r² > 0, without branches (both vanish at and beyond the
  // support, so a pair of a Verlet list outside it contributes zero), with one square root and at most one
  // division. Equal to w(r) and dw(r)/r up to round-off. T must be type().
  template <Type T>
  void w_and_dw_over_r(double r2, double& w, double& dw_over_r) const;

 private:
  Type type_;
  double h_, support_, sigma_;
  double inv_h_, sigma_over_h_, sigma_over_h2_;
};

template <>
inline void SmoothingKernel::w_and_dw_over_r<SmoothingKernel::Type::quintic>(double r2, double& w,
                                                                              double& dw_over_r) const {
  const double r = std::sqrt(r2), q = r * inv_h_;
  const double a = std::max(0.0, 3.0 - q), b = std::max(0.0, 2.0 - q), c = std::max(0.0, 1.0 - q);
  const double a4 = (a * a) * (a * a), b4 = (b * b) * (b * b), c4 = (c * c) * (c * c);
  w = sigma_ * (a4 * a - 6.0 * (b4 * b) + 15.0 * (c4 * c));
  dw_over_r = sigma_over_h_ * (-5.0 * a4 + 30.0 * b4 - 75.0 * c4) / r;
}

template <>
inline void SmoothingKernel::w_and_dw_over_r<SmoothingKernel::Type::wendland_c2>(double r2, double& w,
                                                                                double& dw_over_r) const {
  // w'(r)/r = −5 σ t³ / h² with t = 1 − q/2: no division.
  const double q = std::sqrt(r2) * inv_h_, t = std::max(0.0, 1.0 - 0.5 * q), t3 = t * t * t;
  w = sigma_ * t3 * t * (2.0 * q + 1.0);
  dw_over_r = -5.0 * sigma_over_h2_ * t3;
}

template <>
struct EnumNames<SmoothingKernel::Type> {
  static constexpr std::array<std::pair<SmoothingKernel::Type, std::string_view>, 2> table{
      {{SmoothingKernel::Type::quintic, "quintic"}, {SmoothingKernel::Type::wendland_c2, "wendland_c2"}}};
};

}  // namespace closurelab
