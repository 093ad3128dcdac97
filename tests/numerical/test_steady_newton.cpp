// The `newton` integrator (core/reduced/integrator.hpp): the column model's steady state in one solve of the rate's
// probed Jacobian, against the same model marched to steady state by backward Euler (the committed near-wall
// formulation: force-density balance, coarse–fine Tikhonov with the zero-end first difference), with a tight steady
// tolerance, so that what separates them is the march's remaining transient.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/registry.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "tests/support/config_error.hpp"

using namespace closurelab;
using closurelab::test_support::config_error;

namespace {

json near_wall_cell(const std::string& integrator, const std::string& mode = "steady") {
  return {
      {"scene", {{"name", "poiseuille-uniform"}, {"n_y", 48}, {"n_x", 12}, {"eta_over_ly", 0.0625}}},
      {"closure",
       {{"deconvolver",
         {{"name", "tikhonov"}, {"alpha", 1e-6}, {"regularizer", "first_difference_zero_ends"}, {"backend", "dual"}}},
        {"discretization", "coarse_fine"}}},
      {"quadrature", {{"name", "coarse"}, {"stride_x", 0}, {"stride_y", 4}}},
      {"solver",
       {{"mode", mode},
        {"target_time", 0.1},
        {"scheme", "staggered"},
        {"wall_constraint_forces", true},
        {"balance", "force_density"},
        {"wall_node_value", "reconstructed"},
        {"time_integration", integrator},
        {"steady_tolerance", 1e-10},
        {"max_time", 50.0}}},
      {"reference", {{"direct_sph", false}}}};
}

json run(const json& cell) {
  const Registry& reg = builtin_registry();
  const ExperimentKind& kind = reg.experiments.get("reduced_model", "");
  return kind.run(kind.resolve(cell, "", reg), reg, [](const std::string&) {});
}

}  // namespace

TEST(SteadyNewton, EqualsTheMarchedSteadyStateOfTheNearWallColumn) {
  const json marched = run(near_wall_cell("backward_euler"));
  const json solved = run(near_wall_cell("newton"));
  ASSERT_EQ(marched.at("status"), "ok");
  ASSERT_EQ(solved.at("status"), "ok") << solved.dump();
  const std::vector<double> a = marched.at("profile").at("reduced"), b = solved.at("profile").at("reduced");
  ASSERT_EQ(a.size(), b.size());
  double diff = 0.0, peak = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    peak = std::max(peak, std::abs(a[k]));
  }
  std::cout << "newton against backward Euler marched to a 1e-10 change: " << diff / peak << " of the peak, "
            << marched.at("cost").at("steps") << " steps against " << solved.at("cost").at("steps") << "\n";
  EXPECT_GT(peak, 0.0);
  EXPECT_LT(diff, 1e-8 * peak);  // the march stops at a relative change of 1e-10 per window, not at the fixed point
  EXPECT_EQ(solved.at("cost").at("steps"), 0);
}

TEST(SteadyNewton, RefusedOutsideASteadyColumnRun) {
  const Registry& reg = builtin_registry();
  const ExperimentKind& column = reg.experiments.get("reduced_model", "");
  const std::string msg = config_error([&] { column.resolve(near_wall_cell("newton", "target_time"), "", reg); });
  EXPECT_NE(msg.find("/solver/time_integration"), std::string::npos) << msg;
  EXPECT_NE(msg.find("set mode to steady"), std::string::npos) << msg;
}
