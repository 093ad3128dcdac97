#include "strategies/kernels/gaussian_segment.hpp"

#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_erf.h>

#include <cmath>
#include <vector>

namespace closurelab {

namespace {

struct GaussLegendre {
  std::vector<double> x, w;  // nodes and weights on [-1, 1]
  explicit GaussLegendre(int n) : x(n), w(n) {
    gsl_integration_glfixed_table* t = gsl_integration_glfixed_table_alloc(n);
    for (int i = 0; i < n; ++i) gsl_integration_glfixed_point(-1.0, 1.0, i, &x[i], &w[i], t);
    gsl_integration_glfixed_table_free(t);
  }
};

const GaussLegendre& gauss_legendre_12() {
  static const GaussLegendre gl(12);
  return gl;
}

}  // namespace

double erfcx(double x) { return std::sqrt(2.0 / M_PI) / gsl_sf_hazard(M_SQRT2 * x); }

double gaussian_segment_integral(const Vec2& a, const Vec2& d, double s0, double s1, double eta) {
  if (!(s1 > s0)) return 0.0;
  const double inv_eta2 = 1.0 / (eta * eta);
  const double dd = d.squaredNorm();
  const auto exponent = [&](double s) { return (a - s * d).squaredNorm() * inv_eta2; };
  // u(s) = |d| (s − s_c) / η with s_c the closest point of the line to the window centre.
  const double dn = std::sqrt(dd);
  double u0 = 0.0, u1 = 0.0, variation = 0.0;
  if (dd > 0.0) {
    const double sc = a.dot(d) / dd;
    u0 = dn * (s0 - sc) / eta;
    u1 = dn * (s1 - sc) / eta;
    variation = (u0 < 0.0 && u1 > 0.0) ? std::max(u0 * u0, u1 * u1) : std::abs(u1 * u1 - u0 * u0);
  }
  if (variation <= 1.0) {
    const auto& gl = gauss_legendre_12();
    const double mid = 0.5 * (s0 + s1), half = 0.5 * (s1 - s0);
    double sum = 0.0;
    for (std::size_t i = 0; i < gl.x.size(); ++i) sum += gl.w[i] * std::exp(-exponent(mid + half * gl.x[i]));
    return half * sum;
  }
  const double pref = 0.5 * std::sqrt(M_PI) * eta / dn;
  if (u0 < 0.0 && u1 > 0.0) {
    const double cross = a.x() * d.y() - a.y() * d.x();
    const double p2 = cross * cross / dd * inv_eta2;  // squared distance of the line to the centre, / η²
    return pref * std::exp(-p2) * (gsl_sf_erf(u1) + gsl_sf_erf(-u0));
  }
  if (u0 >= 0.0) return pref * (std::exp(-exponent(s0)) * erfcx(u0) - std::exp(-exponent(s1)) * erfcx(u1));
  return pref * (std::exp(-exponent(s1)) * erfcx(-u1) - std::exp(-exponent(s0)) * erfcx(-u0));
}

}  // namespace closurelab
