// Error norms of finite data are finite and do not depend on the data's scale. A CSV snapshot
// with velocities of 1e154 gave l2_rel = 0 beside max_rel = 0.5 (the reference's sum of squares overflowed),
// and at 1e200 every l2_rel was NaN (inf / inf), while the row said `ok`.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/metrics.hpp"

using namespace closurelab;

namespace {
Eigen::VectorXd sample(int n, double phase) {
  Eigen::VectorXd v(n);
  for (int k = 0; k < n; ++k) v[k] = std::sin(0.37 * k + phase) + 0.1 * k;
  return v;
}
}  // namespace

// Scaling u and ref by s leaves every relative norm unchanged (to rounding: the scaled sums are the same sums
// of the same ratios; 1e-14 relative is many times the few ulps they differ by).
TEST(MetricsRange, RelativeNormsAreScaleInvariantAcrossTheDoubleRange) {
  const int n = 40;
  const Eigen::VectorXd u = sample(n, 0.3), ref = sample(n, 0.0);
  const std::vector<bool> mask(n, true);
  const double peak = ref.cwiseAbs().maxCoeff();
  const ErrorNorms base = error_norms(u, ref, mask, peak);
  const json base_node = node_error_summary(u, ref, mask, peak);
  const ErrorNorms base_vec = vector_error_norms(u, ref, ref, u, peak);
  ASSERT_GT(base.l2_rel, 0.0);
  for (double s : {1e154, 1e200, 1e300, 1e-160, 1e-300}) {
    SCOPED_TRACE(s);
    const Eigen::VectorXd us = s * u, rs = s * ref;
    const ErrorNorms e = error_norms(us, rs, mask, s * peak);
    EXPECT_NEAR(e.l2_rel, base.l2_rel, 1e-14 * base.l2_rel);
    EXPECT_NEAR(e.max_rel, base.max_rel, 1e-14 * base.max_rel);
    const json j = node_error_summary(us, rs, mask, s * peak);
    EXPECT_NEAR(j["l2_rel"].get<double>(), base_node["l2_rel"].get<double>(), 1e-14 * base.l2_rel);
    EXPECT_NEAR(j["max_rel"].get<double>(), base_node["max_rel"].get<double>(), 1e-14 * base.max_rel);
    const ErrorNorms v = vector_error_norms(us, rs, rs, us, s * peak);
    EXPECT_NEAR(v.l2_rel, base_vec.l2_rel, 1e-14 * base_vec.l2_rel);
    EXPECT_NEAR(v.max_rel, base_vec.max_rel, 1e-14 * base_vec.max_rel);
  }
}

// Ordinary data keep their plain sums bit for bit (committed tables must not move by an ulp).
TEST(MetricsRange, OrdinaryDataUseThePlainSums) {
  const int n = 25;
  const Eigen::VectorXd u = sample(n, 1.1), ref = sample(n, 0.2);
  const std::vector<bool> mask(n, true);
  double num = 0, den = 0;
  for (int k = 0; k < n; ++k) {
    num += (u[k] - ref[k]) * (u[k] - ref[k]);
    den += ref[k] * ref[k];
  }
  EXPECT_EQ(error_norms(u, ref, mask, 1.0).l2_rel, std::sqrt(num / den));
  EXPECT_EQ(node_error_summary(u, ref, mask, 1.0)["l2_rel"].get<double>(), std::sqrt(num / den));
  EXPECT_EQ(robust_norm(u), u.norm());
}

// Non-finite data give a non-finite (JSON null) norm, never a finite-looking number.
TEST(MetricsRange, NonFiniteDataGiveNonFiniteNorms) {
  Eigen::VectorXd u = sample(5, 0.0), ref = sample(5, 1.0);
  u[2] = INFINITY;
  const std::vector<bool> mask(5, true);
  EXPECT_FALSE(std::isfinite(error_norms(u, ref, mask, 1.0).l2_rel));
  EXPECT_FALSE(std::isfinite(error_norms(u, ref, mask, 1.0).max_rel));
  EXPECT_FALSE(std::isfinite(robust_norm(u)));
  EXPECT_DOUBLE_EQ(robust_norm(Eigen::VectorXd::Constant(4, 1e200)), 2e200);
}

// A degenerate scale is no scale. A reference at rest (scale 0) used to turn max_rel into the absolute
// error, and one particle at 1e160 made the peak speed overflow (plain squaring), the scale infinite and every
// max_rel 0.0, `ok`. Now both norms are null for a zero, negative, infinite or NaN scale, never an absolute or zero
// error read as relative; the speeds come from hypot, so 1e160 stays finite.
TEST(MetricsRange, AnUnusableScaleGivesNullNorms) {
  const int n = 6;
  const Eigen::VectorXd u = sample(n, 0.4), ref = sample(n, 0.0);
  const std::vector<bool> mask(n, true);
  for (double scale : {0.0, -1.0, double(INFINITY), double(NAN)}) {
    SCOPED_TRACE(scale);
    EXPECT_FALSE(usable_scale(scale));
    const ErrorNorms e = error_norms(u, ref, mask, scale);
    EXPECT_TRUE(std::isnan(e.max_rel) && std::isnan(e.l2_rel));
    EXPECT_TRUE(e.to_json()["max_rel"].is_null() && e.to_json()["l2_rel"].is_null());
    EXPECT_EQ(e.to_json()["count"], n);
    const ErrorNorms v = vector_error_norms(u, u, ref, ref, scale);
    EXPECT_TRUE(v.to_json()["max_rel"].is_null() && v.to_json()["l2_rel"].is_null());
  }
  EXPECT_TRUE(usable_scale(1e-300) && usable_scale(1e300));
  // A reference that vanishes on the subset has no relative l2 error unless the difference vanishes too.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  EXPECT_TRUE(error_norms(u, zero, mask, 1.0).to_json()["l2_rel"].is_null());
  EXPECT_EQ(error_norms(zero, zero, mask, 1.0).l2_rel, 0.0);
  // The peak metric has no peak to be relative to when the reference's is not positive.
  EXPECT_TRUE(std::isnan(peak_relative_difference(u, zero)));
}

TEST(MetricsRange, SpeedsOf1e160StayFinite) {
  Eigen::VectorXd x(3), y(3);
  x << 1e160, 3.0, -1e-200;
  y << 1e160, 4.0, 0.0;
  const Eigen::VectorXd s = vector_magnitudes(x, y);
  EXPECT_DOUBLE_EQ(s[0], std::sqrt(2.0) * 1e160);  // plain squaring gives inf
  EXPECT_DOUBLE_EQ(s[1], 5.0);
  EXPECT_DOUBLE_EQ(s[2], 1e-200);  // plain squaring gives 0
  // The scale from those speeds is usable, and a reduced field of order one against it has max_rel about 1, not 0.
  const Eigen::VectorXd u = Eigen::VectorXd::Ones(3);
  const ErrorNorms e = vector_error_norms(u, u, x, y, s.maxCoeff());
  EXPECT_NEAR(e.max_rel, 1.0, 1e-12);
}
