// The Taylor–Green validation (kind direct_sph_validation on the taylor-green scene) is the direct reference of the
// vortex's transient: its run goes through the reference store with the particles saved at the 20 times where it
// measures max|v| (experiments/kinds/taylor_green_validation.hpp), so the stored entry's particles.h5part holds one
// Step#k per saved time, then the final state, and a second cell reads the same run back instead of recomputing it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "core/base/registry.hpp"
#include "core/io/h5part.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "experiments/kinds/taylor_green_validation.hpp"

using namespace closurelab;
namespace fs = std::filesystem;

TEST(TaylorGreenReference, TheValidationStoresItsParticlesAtTheSavedTimesAndReusesThem) {
  const fs::path store = fs::temp_directory_path() / ("closurelab_tg_reference_" + std::to_string(::getpid()));
  fs::remove_all(store);
  const std::string before = reference_store().dir().string();
  configure_reference_store(store.string(), false);
  const Registry& reg = builtin_registry();
  const ExperimentKind& kind = reg.experiments.get("direct_sph_validation", "");
  const json cell = {{"scene", {{"name", "taylor-green"}, {"n", 16}, {"perturbation", 0.3}, {"h_over_dx", 1.5}}},
                     {"kernel", {{"name", "gaussian"}}},
                     {"solver",
                      {{"formulation", "transport_velocity"}, {"mode", "target_time"}, {"target_time", 0.1},
                       {"max_time", 0.1}}},
                     {"averaging", {{"mesh_spacing_over_eta", 0.25}}}};
  const json cfg = kind.resolve(cell, "", reg);
  const json first = kind.run(cfg, reg, [](const std::string&) {});
  const json second = kind.run(cfg, reg, [](const std::string&) {});
  configure_reference_store(before, false);
  ASSERT_EQ(first.at("status"), "ok") << first.dump();
  const json& store_record = first.at("direct_sph").at("reference_store");
  EXPECT_FALSE(store_record.at("reused").get<bool>());
  EXPECT_TRUE(second.at("direct_sph").at("reference_store").at("reused").get<bool>());
  EXPECT_EQ(second.at("errors"), first.at("errors"));

  const std::string file = (store / store_record.at("entry").get<std::string>() / "particles.h5part").string();
  const std::vector<ParticleSnapshot> steps = read_h5part_all(file);
  const std::vector<double> saved = transient_saved_times(0.1);
  ASSERT_EQ(saved.size(), 20u);
  ASSERT_EQ(steps.size(), saved.size() + 1);  // the saved times, then the final state
  const json& ms = first.at("errors").at("max_speed");
  for (std::size_t k = 0; k < saved.size(); ++k) {
    EXPECT_EQ(steps[k].time, saved[k]) << k;
    EXPECT_EQ(steps[k].particles.size(), 256u);
    double v2 = 0.0;
    for (std::size_t a = 0; a < steps[k].particles.size(); ++a)
      v2 = std::max(v2, steps[k].particles.vx[a] * steps[k].particles.vx[a] +
                            steps[k].particles.vy[a] * steps[k].particles.vy[a]);
    EXPECT_EQ(ms.at("times")[k].get<double>(), saved[k]);
    EXPECT_EQ(ms.at("computed")[k].get<double>(), std::sqrt(v2)) << k;  // the row is read from the stored steps
  }
  EXPECT_EQ(steps.back().particles.x, steps[saved.size() - 1].particles.x);  // the last saved time is the end
  // The averaged particles against the averaged exact field at each saved time (the reduced model's reference).
  const json& avg = first.at("errors").at("averaged_vs_averaged_exact");
  ASSERT_EQ(avg.at("max_rel").size(), saved.size());
  ASSERT_EQ(avg.at("l2_rel").size(), saved.size());
  EXPECT_GT(avg.at("window_factor").get<double>(), 0.5);
  EXPECT_LT(avg.at("window_factor").get<double>(), 1.0);
  for (std::size_t k = 0; k < saved.size(); ++k) {
    EXPECT_TRUE(std::isfinite(avg.at("l2_rel")[k].get<double>())) << k;
    EXPECT_LE(avg.at("max_rel")[k].get<double>(), avg.at("worst_max_rel").get<double>()) << k;
  }
  fs::remove_all(store);
}
