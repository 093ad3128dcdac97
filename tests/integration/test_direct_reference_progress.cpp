// A direct reference's steady test on a fine observation mesh (observe_spacing_over_eta = 0.01 on a
// 2D reference once took 72 s with one progress line): the run says up front how many nodes each average fills, and each
// average slower than 2 s is reported (progress interval 0 here: every one).
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "core/base/registry.hpp"
#include "experiments/kinds/direct_reference.hpp"

using namespace closurelab;

TEST(DirectReferenceProgress, AFineObservationMeshIsAnnouncedAndSlowAveragesReported) {
  const Registry& reg = builtin_registry();
  const auto scene = reg.scenes.create(json{{"name", "cellular"}, {"n", 32}, {"eta_over_l", 0.125}}, "/scene");
  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
  SphRunOptions opt;
  opt.to_steady_state = false;
  opt.target_time = 30 * direct_step_bound(*scene, opt.kappa);  // about 30 steps: 3 averages at window 10
  opt.steady_window = 10;
  opt.progress_seconds = 0.0;
  std::vector<std::string> lines;
  opt.progress = [&](const std::string& l) { lines.push_back(l); };
  const TensorMesh2D mesh = observe_mesh(*scene, 0.01 * scene->eta);  // 800 x 800 nodes
  ASSERT_EQ(mesh.size(), 640000);
  const DirectReference d = run_direct_reference(*scene, *kernel, opt, mesh);
  EXPECT_EQ(d.run.status, Status::target_time) << d.run.message;
  ASSERT_FALSE(lines.empty());
  EXPECT_NE(lines.front().find("averages 1024 particles onto 640000 nodes"), std::string::npos) << lines.front();
  const std::regex took("average ([0-9]+) onto 640000 nodes took ([0-9.e+-]+) s");
  int reported = 0;
  for (const std::string& l : lines) {
    std::smatch m;
    if (!std::regex_search(l, m, took)) continue;
    ++reported;
    EXPECT_GE(std::stod(m[2].str()), 2.0) << l;  // only slow averages are reported
  }
  std::printf("%d of the averages took 2 s or more here\n", reported);
  // A coarse mesh (the default 0.25 eta') is not announced.
  lines.clear();
  run_direct_reference(*scene, *kernel, opt, observe_mesh(*scene, 0.25 * scene->eta));
  for (const std::string& l : lines) EXPECT_EQ(l.find("the steady test averages"), std::string::npos) << l;
}
