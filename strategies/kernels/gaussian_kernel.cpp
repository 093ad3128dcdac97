#include "strategies/kernels/gaussian_kernel.hpp"

#include <gsl/gsl_integration.h>

#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/gsl_support.hpp"
#include "strategies/kernels/gaussian_segment.hpp"

namespace closurelab {

GaussianKernel::GaussianKernel(double eta) : eta_(eta) {
  if (!(eta > 0) || !std::isfinite(eta)) throw ConfigError("/eta", "eta must be a positive finite number");
}

double GaussianKernel::factor(double t) const { return std::exp(-t * t / (eta_ * eta_)) / (std::sqrt(M_PI) * eta_); }

double GaussianKernel::factor_derivative(double t) const { return -2.0 * t / (eta_ * eta_) * factor(t); }

double GaussianKernel::factor_symbol(double xi) const { return std::exp(-M_PI * M_PI * eta_ * eta_ * xi * xi); }

double GaussianKernel::bond_integral(const Vec2& x, const Vec2& qj, const Vec2& qk) const {
  // (A.1): the segment from x − q_j (s = 0) to x − q_k (s = 1).
  return gaussian_segment_integral(x - qj, qk - qj, 0.0, 1.0, eta_) / (M_PI * eta_ * eta_);
}

CutoffGaussianKernel::CutoffGaussianKernel(double eta, double cutoff_in_eta) : eta_(eta), rc_(cutoff_in_eta * eta) {
  if (!(eta > 0) || !std::isfinite(eta)) throw ConfigError("/eta", "eta must be a positive finite number");
  if (!(cutoff_in_eta > 0)) throw ConfigError("/cutoff", "cutoff must be positive");
  z_ = std::erf(cutoff_in_eta);
}

double CutoffGaussianKernel::factor(double t) const {
  if (std::abs(t) > rc_) return 0.0;
  return std::exp(-t * t / (eta_ * eta_)) / (std::sqrt(M_PI) * eta_ * z_);
}

double CutoffGaussianKernel::factor_derivative(double t) const { return -2.0 * t / (eta_ * eta_) * factor(t); }

double CutoffGaussianKernel::factor_symbol(double xi) const {
  struct P {
    const CutoffGaussianKernel* k;
    double xi;
  } p{this, xi};
  gsl_errors_as_status();
  gsl_function f;
  f.function = [](double t, void* v) {
    auto* q = static_cast<P*>(v);
    return q->k->factor(t) * std::cos(2.0 * M_PI * q->xi * t);
  };
  f.params = &p;
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(1000);
  double result = 0.0, err = 0.0;
  gsl_integration_qag(&f, -rc_, rc_, 1e-15, 1e-13, 1000, GSL_INTEG_GAUSS61, w, &result, &err);
  gsl_integration_workspace_free(w);
  return result;
}

double CutoffGaussianKernel::bond_integral(const Vec2& x, const Vec2& qj, const Vec2& qk) const {
  const Vec2 a = x - qj, d = qk - qj;
  // The parameters s for which a − s d lies in the box |·|_∞ <= r_c form one interval.
  double lo = 0.0, hi = 1.0;
  for (int c = 0; c < 2; ++c) {
    if (d[c] == 0.0) {
      if (std::abs(a[c]) > rc_) return 0.0;
      continue;
    }
    double s_a = (a[c] - rc_) / d[c], s_b = (a[c] + rc_) / d[c];
    if (s_a > s_b) std::swap(s_a, s_b);
    lo = std::max(lo, s_a);
    hi = std::min(hi, s_b);
  }
  if (!(hi > lo)) return 0.0;
  return gaussian_segment_integral(a, d, lo, hi, eta_) / (M_PI * eta_ * eta_ * z_ * z_);
}

}  // namespace closurelab
