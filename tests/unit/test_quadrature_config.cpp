// Stress-quadrature configuration: registration, parameter validation and clear errors before running.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"
#include "strategies/quadrature/coarse_quadrature.hpp"
#include "strategies/quadrature/exact_quadrature.hpp"
#include "tests/support/quadrature_support.hpp"

using namespace closurelab;
using namespace closurelab::quadrature_test;

namespace {

// The ConfigError thrown by `f`, or a failure.
template <class F>
ConfigError config_error(F f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no ConfigError";
  return ConfigError("", "");
}

}  // namespace

TEST(QuadratureConfig, BothQuadraturesAreRegisteredWithResolvedDefaults) {
  const Registry& r = builtin_registry();
  ASSERT_TRUE(r.quadratures.contains("exact"));
  ASSERT_TRUE(r.quadratures.contains("coarse"));
  const json c = r.quadratures.resolve(json{{"name", "coarse"}}, "/quadrature");
  EXPECT_EQ(c.at("stride_y"), 4);
  EXPECT_EQ(c.at("stride_x"), 0);
  EXPECT_EQ(c.at("wall_band"), "coarse");  // plain (5.27), as in the paper
  EXPECT_EQ(r.quadratures.create(json{{"name", "exact"}}, "/q")->name(), "exact");
}

TEST(QuadratureConfig, OutOfRangeOrUnknownParametersNameThePath) {
  const Registry& r = builtin_registry();
  EXPECT_NE(config_error([&] { r.quadratures.create(json{{"name", "coarse"}, {"stride_y", 0}}, "/q"); }).path().find("/q/stride_y"),
            std::string::npos);
  EXPECT_NE(config_error([&] { r.quadratures.create(json{{"name", "coarse"}, {"stride_x", -1}}, "/q"); }).path().find("/q/stride_x"),
            std::string::npos);
  EXPECT_NE(config_error([&] { r.quadratures.create(json{{"name", "coarse"}, {"factor", 16}}, "/q"); }).path().find("/q"),
            std::string::npos);
  EXPECT_NE(std::string(config_error([&] { r.quadratures.create(json{{"name", "simpson"}}, "/q"); }).what()).find("coarse"),
            std::string::npos);
}

TEST(QuadratureConfig, RGridThatDoesNotTileTheLatticeIsRejectedAtSetup) {
  const auto s = channel(48);  // n_y = 48, n_x = 12
  const GaussianKernel k(s->eta);
  const TensorMesh2D mesh = column_mesh(s->box, s->eta);
  {
    CoarseQuadrature q(0, 5);
    const ConfigError e = config_error([&] { q.setup(*s, k, mesh, {"xy"}); });
    EXPECT_EQ(e.path(), "/stride_y");
    EXPECT_NE(e.message().find("1, 2, 3, 4, 6, 8, 12, 16, 24, 48"), std::string::npos) << e.message();
  }
  {
    CoarseQuadrature q(5, 4);
    EXPECT_EQ(config_error([&] { q.setup(*s, k, mesh, {"xy"}); }).path(), "/stride_x");
  }
  {
    const Scene box = periodic_box(16, 0.5);  // not x-invariant: the x-integrated column does not apply
    const auto axis = UniformMesh1D::cell_centred(0.0, 0.5, 8, true);
    CoarseQuadrature q(0, 4);
    EXPECT_EQ(config_error([&] { q.setup(box, k, TensorMesh2D{axis, axis}, {"xy"}); }).path(), "/stride_x");
  }
}

TEST(QuadratureConfig, MeshOrComponentsUnfitForTheSceneAreRejected) {
  const auto s = channel(48);
  const GaussianKernel k(s->eta);
  const TensorMesh2D not_periodic{UniformMesh1D::cell_centred(0.0, s->box.lx, 1, false),
                                  UniformMesh1D::cell_centred(0.0, 1.0, 16, false)};
  for (auto* q : std::vector<StressQuadrature*>{new ExactQuadrature, new CoarseQuadrature(0, 4)}) {
    std::unique_ptr<StressQuadrature> owner(q);
    config_error([&] { q->setup(*s, k, not_periodic, {"xy"}); });
    config_error([&] { q->setup(*s, k, column_mesh(s->box, s->eta), {"zz"}); });
    config_error([&] { q->setup(*s, k, column_mesh(s->box, s->eta), {}); });
  }
}

TEST(QuadratureConfig, MisuseIsReportedNotIgnored) {
  const auto s = channel(48);
  const GaussianKernel k(s->eta);
  ExactQuadrature q;
  const VelocitySampler none = [](const std::vector<Vec2>&) { return Eigen::Matrix2Xd(2, 0); };
  EXPECT_THROW(q.evaluate(none), std::logic_error);  // before setup
  q.setup(*s, k, column_mesh(s->box, s->eta), {"xy"});
  EXPECT_THROW(q.evaluate(none), std::logic_error);  // a sampler that breaks its contract
  CoarseQuadrature c(0, 4);
  c.setup(*s, k, column_mesh(s->box, s->eta), {"xy"});
  EXPECT_THROW(c.evaluate(none), std::logic_error);
  // A non-finite velocity field is a numerical issue with a reason, as in a deconvolution.
  const VelocitySampler nan = [](const std::vector<Vec2>& p) {
    return Eigen::Matrix2Xd::Constant(2, static_cast<Eigen::Index>(p.size()), std::nan(""));
  };
  for (StressQuadrature* quad : std::initializer_list<StressQuadrature*>{&q, &c}) {
    const QuadratureResult r = quad->evaluate(nan);
    EXPECT_EQ(r.status, Status::numerical_issue);
    EXPECT_NE(r.message.find("non-finite"), std::string::npos) << r.message;
  }
  // The cost of the coarse quadrature does not depend on N: the same R-grid on a strip 8x wider.
  const auto wide = channel(48, 1.0 / 16, 96);
  CoarseQuadrature c2(0, 4);
  c2.setup(*wide, k, column_mesh(wide->box, wide->eta), {"xy"});
  EXPECT_EQ(c2.virtual_pairs(), c.virtual_pairs());
  EXPECT_EQ(c2.r_nodes(), 12);
  EXPECT_DOUBLE_EQ(c2.coarsening(), 96.0 * 4.0);
}

TEST(QuadratureConfig, ExperimentCellWithABadRGridFailsBeforeRunning) {
  const Registry& r = builtin_registry();
  const ExperimentKind& kind = builtin_registry().experiments.get("quadrature_convergence", "/kind");
  const json cell = {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 48}}},
                     {"quadrature", {{"name", "coarse"}, {"stride_y", 5}}}};
  EXPECT_EQ(config_error([&] { kind.resolve(cell, "/cells/0", r); }).path(), "/cells/0/quadrature/stride_y");
  json ok = cell;
  ok["quadrature"]["stride_y"] = 4;
  const json resolved = kind.resolve(ok, "/cells/0", r);
  EXPECT_EQ(resolved.at("evaluation").at("velocity"), "analytic");
  EXPECT_EQ(resolved.at("quadrature").at("wall_band"), "coarse");
}
