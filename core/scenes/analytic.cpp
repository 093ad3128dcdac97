#include "core/scenes/analytic.hpp"

#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/base/gsl_support.hpp"

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

LayeredChannelFlow::LayeredChannelFlow(double l1, double l2, std::vector<double> interfaces,
                                       std::vector<double> viscosity, double rho, double g)
    : l1_(l1), l2_(l2), rho_g_(rho * g), mu_(std::move(viscosity)) {
  if (!(l2 > l1)) throw std::invalid_argument("LayeredChannelFlow: need l1 < l2");
  if (mu_.size() != interfaces.size() + 1)
    throw std::invalid_argument("LayeredChannelFlow: need one viscosity per segment (interfaces + 1)");
  for (double m : mu_)
    if (!(m > 0.0)) throw std::invalid_argument("LayeredChannelFlow: viscosities must be > 0");
  start_.push_back(l1);
  for (double y : interfaces) {
    if (!(y > start_.back() && y < l2)) throw std::invalid_argument("LayeredChannelFlow: interfaces must ascend inside (l1, l2)");
    start_.push_back(y);
  }
  // Per segment k on [a, b): ∫_a^b ds/μ_k = (b − a)/μ_k and ∫_a^b (s − l1) ds/μ_k = (b − a)(a + b − 2 l1)/(2 μ_k);
  // v(l2) = C Σ (b − a)/μ_k − ρg Σ (b − a)(a + b − 2 l1)/(2 μ_k) = 0.
  double compliance = 0.0, moment = 0.0;
  for (std::size_t k = 0; k < mu_.size(); ++k) {
    const double a = start_[k], b = k + 1 < start_.size() ? start_[k + 1] : l2;
    compliance += (b - a) / mu_[k];
    moment += (b - a) * (a + b - 2.0 * l1) / (2.0 * mu_[k]);
  }
  shear_at_l1_ = rho_g_ * moment / compliance;
  v_start_.assign(mu_.size(), 0.0);
  for (std::size_t k = 0; k + 1 < mu_.size(); ++k) {
    const double a = start_[k], b = start_[k + 1];
    v_start_[k + 1] = v_start_[k] + (shear_at_l1_ * (b - a) - 0.5 * rho_g_ * (b - a) * (a + b - 2.0 * l1)) / mu_[k];
  }
}

std::size_t LayeredChannelFlow::segment(double y) const {
  return static_cast<std::size_t>(std::upper_bound(start_.begin(), start_.end(), y) - start_.begin()) - 1;
}

double LayeredChannelFlow::velocity(double y) const {
  if (y <= l1_ || y >= l2_) return 0.0;
  const std::size_t k = segment(y);
  const double a = start_[k];
  return v_start_[k] + (shear_at_l1_ * (y - a) - 0.5 * rho_g_ * (y - a) * (y + a - 2.0 * l1_)) / mu_[k];
}

double LayeredChannelFlow::viscosity(double y) const {
  if (y <= l1_) return mu_.front();
  if (y >= l2_) return mu_.back();
  return mu_[segment(y)];
}

double LayeredChannelFlow::peak_height() const {
  return rho_g_ != 0.0 ? std::clamp(l1_ + shear_at_l1_ / rho_g_, l1_, l2_) : 0.5 * (l1_ + l2_);
}

Vec2 cellular_mode(double x, double y, double k) {
  return {std::sin(k * x) * std::cos(k * y), -std::cos(k * x) * std::sin(k * y)};
}

double cellular_pressure(double x, double y, double k, double rho, double amplitude) {
  return 0.25 * rho * amplitude * amplitude * (std::cos(2.0 * k * x) + std::cos(2.0 * k * y));
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
                             double radius, double y, double lo, double hi, const std::vector<double>& breakpoints) {
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
  std::vector<double> edges{a};
  for (double t : breakpoints)
    if (t > a && t < b) edges.push_back(t);
  std::sort(edges.begin() + 1, edges.end());
  edges.push_back(b);
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(2000);
  double total = 0.0;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    double result = 0.0, err = 0.0;
    gsl_integration_qag(&F, edges[k], edges[k + 1], 1e-15, 1e-12, 2000, GSL_INTEG_GAUSS41, w, &result, &err);
    total += result;
  }
  gsl_integration_workspace_free(w);
  return total;
}

}  // namespace closurelab
