#include "core/analytic.hpp"

#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>

#include "core/gsl_support.hpp"

namespace closurelab {

double poiseuille_velocity(double y, double l1, double l2, double rho, double g, double mu) {
  if (y <= l1 || y >= l2) return 0.0;
  return -rho * g / (2.0 * mu) * (y * y - (l1 + l2) * y + l1 * l2);
}

double periodic_force_velocity(double y, double l1, double l2, double rho, double g, double mu, double amplitude,
                               double n) {
  if (y <= l1 || y >= l2) return 0.0;
  const double w = l2 - l1;
  return rho * g / (2.0 * mu) * ((l1 + l2) * y - l1 * l2) -
         rho * g / mu * (0.5 * y * y - amplitude * w * w / (n * n * M_PI * M_PI) * std::sin((y - l1) / w * n * M_PI));
}

double poiseuille_averaged_b2(double y, double l1, double l2, double rho, double g, double mu, double eta) {
  return -rho * g / (2.0 * mu) * (0.5 * eta * eta + y * y - (l1 + l2) * y + l1 * l2);
}

double poiseuille_convective_stress_b(double y, double l1, double l2, double rho, double g, double mu, double eta) {
  const double k = rho * g / (2.0 * mu);
  const double v = -k * (y * y - (l1 + l2) * y + l1 * l2);  // continued parabola
  const double vbar = poiseuille_averaged_b2(y, l1, l2, rho, g, mu, eta);
  const double s = l1 + l2 - 2.0 * y;
  // As printed in Appendix B (with ρ = 1 in its prefactors).
  return k * k * (0.25 * std::pow(eta, 4) + 0.5 * s * s * eta * eta) - k * vbar * eta * eta + v * v - vbar * vbar;
}

double average_by_quadrature(const std::function<double(double)>& f, const std::function<double(double)>& phi,
                             double radius, double y, double lo, double hi) {
  const double a = std::max(lo, y - radius), b = std::min(hi, y + radius);
  if (!(b > a)) return 0.0;
  gsl_errors_as_status();
  struct P {
    const std::function<double(double)>* f;
    const std::function<double(double)>* phi;
    double y;
  } p{&f, &phi, y};
  gsl_function F;
  F.function = [](double t, void* v) {
    auto* q = static_cast<P*>(v);
    return (*q->f)(t) * (*q->phi)(q->y - t);
  };
  F.params = &p;
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(2000);
  double result = 0.0, err = 0.0;
  gsl_integration_qag(&F, a, b, 1e-15, 1e-12, 2000, GSL_INTEG_GAUSS41, w, &result, &err);
  gsl_integration_workspace_free(w);
  return result;
}

}  // namespace closurelab
