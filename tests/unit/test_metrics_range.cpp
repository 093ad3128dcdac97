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
