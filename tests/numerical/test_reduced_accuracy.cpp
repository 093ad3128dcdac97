// Accuracy of the reduced model where the paper makes its claims, at resolutions a test can afford: the
// second-order closure beats the first on Fig. 4's scene (§6), and the two-phase layered channel (§7, the
// headline) against the averaged direct SPH of the same scene. Each cell runs through the reduced_model kind,
// as `closurelab run` does. About 1 s (Fig. 4) and 5 s (two-phase) on one core.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "experiments/kinds/experiment_kind.hpp"

using namespace closurelab;

namespace {

json run_cell(const json& cell) {
  const Registry& reg = builtin_registry();
  const ExperimentKind& kind = builtin_registry().experiments.get("reduced_model", "");
  return kind.run(kind.resolve(cell, "", reg), reg, [](const std::string&) {});
}

double max_rel(const json& row, const char* reference, const char* nodes) {
  return row.at("errors").at(reference).at(nodes).at("max_rel").get<double>();
}

double peak(const json& row, const char* reference) {
  return row.at("errors").at(reference).at("peak_relative_difference").get<double>();
}

}  // namespace

// experiments/paper/fig4.json's cell (poiseuille-periodic A = 5, n = 4, η'/L = 0.07, Landweber cc, staggered,
// wall constraint forces) at n_y = 48 instead of 192, with the R-grid spacing of its N/N_C = 32 row (stride_y 4
// of 192 = stride_y 1 of 48; x-integrated), against the Gaussian average of (D.3) at the coarse nodes.
// Measured, max error over every coarse node / analytic peak, orders 0, 1, 2: 0.444, 0.283, 0.244 (n_y = 192 in
// results/paper/fig4/summary.md: 0.447, 0.284, 0.244); peak metric 0.344, 0.214, 0.186. Asserted: each order
// beats the one below by a margin (2 vs 1: ratio 0.861, asserted < 0.9), each within 10 % of its measurement.
TEST(ReducedAccuracy, SecondOrderBeatsFirstOnFig4sScene) {
  const json spec = read_json_file(std::string(CLOSURELAB_SOURCE_DIR) + "/experiments/paper/fig4.json");
  double err[3], pk[3];
  for (int order : {0, 1, 2}) {
    json cell = spec.at("base");
    cell["scene"]["n_y"] = 48;
    cell["scene"]["n_x"] = 12;
    cell["quadrature"] = {{"name", "coarse"}, {"stride_x", 0}, {"stride_y", 1}};
    cell["reference"]["direct_sph"] = false;
    cell["closure"]["deconvolver"]["order"] = order;
    const json row = run_cell(cell);
    ASSERT_EQ(row.at("status"), "ok") << row.at("reduced_model").dump();
    err[order] = max_rel(row, "vs_averaged_analytic", "all_nodes");
    pk[order] = peak(row, "vs_averaged_analytic");
    std::printf("order %d: max error %.4f, peak metric %.4f (vs the averaged analytic solution)\n", order, err[order], pk[order]);
  }
  EXPECT_LT(err[1], 0.7 * err[0]);
  EXPECT_LT(err[2], 0.9 * err[1]);
  EXPECT_LT(pk[2], pk[1]);
  EXPECT_LT(pk[1], pk[0]);
  const double measured[3] = {0.444, 0.283, 0.244};
  for (int order : {0, 1, 2}) EXPECT_LT(err[order], 1.1 * measured[order]) << "order " << order;
}

// §7, case 3 (two less-viscous layers of width 27 rows of 192, μ = 200/100, van der Waals EOS) at n_y = 32 (the
// layers scaled to 5 rows at rows 5 and 20), η' = L/16, the two_phase.json setup (coarse quadrature, x-integrated,
// staggered scheme, wall constraint forces) with the coarse quadrature at stride 1, against the averaged direct
// SPH of the same strip at t = 0.012 (steady: the slowest viscous mode is down by e^{−11.8}). Measured, max error
// over the fluid nodes / analytic peak, and the paper's peak metric: order 0: 0.0456, 0.0125; order 2: 0.0162,
// 0.0070 (the paper: <= 2 % for case 3). The wall-surface nodes carry the imposed v̄ = 0 of (5.6), 0.080 away
// from the direct average for every closure. Against the average of the analytic piecewise parabolas, order 2:
// 0.065 (the direct SPH's zero-velocity wall overpredicts by about 2ε'/W = 6 % at this n_y, DESIGN.md §6).
TEST(ReducedAccuracy, TwoPhaseLayeredChannelFollowsTheDirectSph) {
  double fluid[3], pk[3];
  for (int order : {0, 2}) {
    const json cell = {
        {"scene", {{"name", "layered-two-phase"}, {"case", "case3"}, {"n_y", 32}, {"n_x", 12}, {"eta_over_l", 0.0625}}},
        {"closure", {{"deconvolver", {{"name", "landweber"}, {"order", order}}}, {"discretization", "coarse_coarse"}}},
        {"quadrature", {{"name", "coarse"}, {"stride_x", 0}, {"stride_y", 1}}},
        {"solver", {{"mode", "steady"}, {"scheme", "staggered"}, {"wall_constraint_forces", true}, {"max_time", 1.0}}},
        {"reference", {{"direct_sph", true}, {"solver", {{"mode", "target_time"}, {"target_time", 0.012}}}}}};
    const json row = run_cell(cell);  // the direct reference runs once per process (cached by the kind)
    ASSERT_EQ(row.at("status"), "ok") << row.at("reduced_model").dump();
    fluid[order] = max_rel(row, "vs_averaged_direct_sph", "fluid_nodes");
    pk[order] = peak(row, "vs_averaged_direct_sph");
    const double analytic = max_rel(row, "vs_averaged_analytic", "all_nodes");
    std::printf("order %d: vs averaged direct SPH: max over fluid nodes %.4f, peak %.4f, all nodes %.4f; vs averaged "
                "analytic: all nodes %.4f\n",
                order, fluid[order], pk[order], max_rel(row, "vs_averaged_direct_sph", "all_nodes"), analytic);
    if (order == 2) {
      EXPECT_LT(fluid[2], 0.02);             // measured 0.0162
      EXPECT_LT(std::abs(pk[2]), 0.01);      // measured 0.0070; the paper's bound for case 3: 0.02
      EXPECT_LT(analytic, 0.075);            // measured 0.065
    }
  }
  EXPECT_LT(fluid[2], 0.5 * fluid[0]);  // measured ratio 0.36
  EXPECT_LT(std::abs(pk[2]), std::abs(pk[0]));
}
