// Bad configuration and bad data give clear errors naming what is wrong, and
// operators that a method cannot handle give a clear status instead of garbage.
#include <gtest/gtest.h>

#include <limits>

#include "tests/support/config_error.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/base/registry.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {
const auto& decon() { return builtin_registry().deconvolvers; }
using test_support::config_error;
ForwardOperator small_operator() {
  const GaussianKernel k(0.1);
  const UniformMesh1D m = UniformMesh1D::cell_centred(0, 1, 20, false);
  return make_averaging_operator_1d(k, m, m, Discretization::coarse_coarse);
}
}  // namespace

TEST(DeconvBadInput, UnknownMethodListsKnownNames) {
  const std::string e = config_error([] { decon().create(json{{"name", "wiener"}}, "/cells/0/method"); });
  EXPECT_NE(e.find("/cells/0/method"), std::string::npos) << e;
  EXPECT_NE(e.find("tikhonov"), std::string::npos) << e;
}

TEST(DeconvBadInput, UnknownOrIllTypedParameterNamesThePath) {
  std::string e = config_error([] { decon().create(json{{"name", "tikhonov"}, {"alfa", 1e-3}}, "/m"); });
  EXPECT_NE(e.find("/m/alfa"), std::string::npos) << e;
  e = config_error([] { decon().create(json{{"name", "tsvd"}, {"k", "ten"}}, "/m"); });
  EXPECT_NE(e.find("/m/k"), std::string::npos) << e;
  e = config_error([] { decon().create(json{{"name", "cg"}, {"rule", "gcv"}}, "/m"); });
  EXPECT_NE(e.find("/m/rule"), std::string::npos) << e;
}

TEST(DeconvBadInput, NonPositiveAlphaIsRejected) {
  for (double alpha : {0.0, -1e-3}) {
    const std::string e = config_error([&] { decon().create(json{{"name", "tikhonov"}, {"alpha", alpha}}, "/m"); });
    EXPECT_NE(e.find("/m/alpha"), std::string::npos) << e;
  }
}

TEST(DeconvBadInput, TruncationIndexOutOfRangeIsRejectedAtSetup) {
  const ForwardOperator a = small_operator();
  auto d = decon().create(json{{"name", "tsvd"}, {"k", 21}}, "/m");
  const std::string e = config_error([&] { d->setup(a); });
  EXPECT_NE(e.find("/k"), std::string::npos) << e;
  EXPECT_NE(e.find("20"), std::string::npos) << e;
}

TEST(DeconvBadInput, NonFiniteOrMismatchedDataIsRejectedBySolve) {
  const ForwardOperator a = small_operator();
  for (const std::string name : {"landweber", "landweber_relaxed", "tikhonov", "tsvd", "cg", "cgls"}) {
    auto d = decon().create(json{{"name", name}}, "/m");
    d->setup(a);
    Eigen::VectorXd b = Eigen::VectorXd::Ones(20);
    b(3) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(config_error([&] { d->solve(b); }).find("not finite"), std::string::npos) << name;
    EXPECT_NE(config_error([&] { d->solve(Eigen::VectorXd::Ones(19)); }).find("19 entries"), std::string::npos) << name;
    EXPECT_NE(config_error([&] { d->solve(Eigen::VectorXd::Ones(20), -1.0); }).find("noise level"), std::string::npos);
  }
}

TEST(DeconvBadInput, SolveBeforeSetupIsAnError) {
  auto d = decon().create(json{{"name", "cgls"}}, "/m");
  EXPECT_THROW(d->solve(Eigen::VectorXd::Ones(3)), ConfigError);
}

TEST(DeconvBadInput, MethodsThatNeedASquareOperatorSaySo) {
  const GaussianKernel k(0.1);
  const UniformMesh1D c = UniformMesh1D::cell_centred(0, 1, 10, false), f = UniformMesh1D::cell_centred(0, 1, 30, false);
  const ForwardOperator a = make_averaging_operator_1d(k, c, f, Discretization::coarse_fine);
  auto lw = decon().create(json{{"name", "landweber"}}, "/m");
  EXPECT_NE(config_error([&] { lw->setup(a); }).find("square"), std::string::npos);
  auto tp = decon().create(json{{"name", "tikhonov"}, {"form", "paper"}}, "/m");
  EXPECT_NE(config_error([&] { tp->setup(a); }).find("/form"), std::string::npos);
  // CG is refused with a status, not an exception: the operator is data, not configuration.
  auto cg = decon().create(json{{"name", "cg"}}, "/m");
  cg->setup(a);
  const DeconvolutionResult r = cg->solve(Eigen::VectorXd::Ones(10));
  EXPECT_EQ(r.status, DeconvolutionStatus::numerical_issue);
  EXPECT_NE(r.stats.message.find("not square"), std::string::npos) << r.stats.message;
  EXPECT_TRUE(r.x.allFinite());
}

// GCV works with every regularizer and backend now (the general-form Tikhonov); what remains refused: the paper form's
// (A + alpha L'L) x = b has no filter factors, and a regularizer whose null space A annihilates leaves the
// minimizer of ||Ax - b||^2 + alpha ||Lx||^2 not unique.
TEST(DeconvBadInput, TikhonovRefusesTheSpectralPaperFormWithADifferenceAndIntersectingNullSpaces) {
  const ForwardOperator a = small_operator();
  auto p = decon().create(
      json{{"name", "tikhonov"}, {"form", "paper"}, {"backend", "spectral"}, {"regularizer", "first_difference"}}, "/m");
  EXPECT_NE(config_error([&] { p->setup(a); }).find("/backend"), std::string::npos);
  // A that sums to zero on each pair of neighbours maps the constants (null space of the first difference) to 0.
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(10, 20);
  for (int i = 0; i < 10; ++i) {
    m(i, 2 * i) = 1.0;
    m(i, 2 * i + 1) = -1.0;
  }
  const ForwardOperator z = ForwardOperator::from_dense(m);
  auto d = decon().create(json{{"name", "tikhonov"}, {"rule", "gcv"}, {"regularizer", "first_difference"}}, "/m");
  const std::string e = config_error([&] { d->setup(z); });
  EXPECT_NE(e.find("/regularizer"), std::string::npos) << e;
  EXPECT_NE(e.find("not unique"), std::string::npos) << e;
}

TEST(DeconvBadInput, RelaxationTooLargeIsRejected) {
  const ForwardOperator a = small_operator();
  auto d = decon().create(json{{"name", "landweber_relaxed"}, {"omega", 2.5}}, "/m");
  EXPECT_NE(config_error([&] { d->setup(a); }).find("/omega"), std::string::npos);
}
