// A row that is not a result says why (nine committed no_convergence rows had no message).
#include <gtest/gtest.h>

#include "core/base/registry.hpp"
#include "experiments/kinds/experiment_kind.hpp"

using namespace closurelab;

TEST(RowMessages, DirectSphThatStopsAtMaxTimeSaysWhy) {
  const ExperimentKind& kind = builtin_registry().experiments.get("direct_sph_validation", "/kind");
  const json cell = {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 16}}}, {"solver", {{"max_time", 1e-4}}}};
  const json resolved = kind.resolve(cell, "/base", builtin_registry());
  const json row = kind.run(resolved, builtin_registry(), [](const std::string&) {});
  EXPECT_EQ(row.at("status"), "no_convergence");
  ASSERT_TRUE(row.contains("message"));
  const std::string m = row.at("message").get<std::string>();
  EXPECT_NE(m.find("max_time = 0.0001"), std::string::npos) << m;
  EXPECT_NE(m.find("before steady state"), std::string::npos) << m;
  EXPECT_EQ(row.at("direct_sph").at("message"), m);
}
