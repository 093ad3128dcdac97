#pragma once
// SPH smoothing functions w_ε of (5.1)–(5.2) in 2D: the quintic spline (support 3h, Morris et al. 1997)
// and Wendland C2 (support 2h). Both normalized, ∫ w = 1.
#include <array>
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

 private:
  Type type_;
  double h_, support_, sigma_;
};

template <>
struct EnumNames<SmoothingKernel::Type> {
  static constexpr std::array<std::pair<SmoothingKernel::Type, std::string_view>, 2> table{
      {{SmoothingKernel::Type::quintic, "quintic"}, {SmoothingKernel::Type::wendland_c2, "wendland_c2"}}};
};

}  // namespace closurelab
