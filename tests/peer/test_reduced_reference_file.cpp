// A reduced_model cell whose reference is a particle file (reference.file, experiments/kinds/reference_profiles.hpp)
// instead of the direct SPH run: (1) the direct run's own final particles, written in PySPH's HDF5 layout and
// taken as the store's H5Part, give the direct run's errors; (2) the file PySPH itself wrote
// (tests/peer/data/poiseuille_pysph_ny32_t0.1.hdf5, PySPH 1.0b1, t = 0.1) gives the errors of closurelab's direct
// run to the same time; (3) bad files and a file with transient snapshots are ConfigErrors before anything runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/base/params.hpp"
#include "core/io/particle_snapshot.hpp"
#include "tests/peer/reference_file_support.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

const std::string pysph_file = std::string(CLOSURELAB_SOURCE_DIR) + "/tests/peer/data/poiseuille_pysph_ny32_t0.1.hdf5";

json reduced_cell(int n_y, int n_x, double t_end) {
  return {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", n_y}, {"n_x", n_x}}},
          {"quadrature", {{"name", "coarse"}, {"stride_y", 2}}},
          {"solver", {{"mode", "target_time"}, {"target_time", t_end}, {"scheme", "staggered"}}}};
}

}  // namespace

TEST(ReducedReferenceFile, TheDirectRunsOwnParticlesGiveItsErrors) {
  const auto work = fresh_work_folder("reduced_reference_file");
  json base = reduced_cell(32, 12, 0.05);
  base["reference"] = {{"solver", {{"mode", "target_time"}, {"target_time", 0.05}}}};
  const json direct = run_rows(work, "direct", "reduced_model", base, json::object());
  ASSERT_EQ(direct.size(), 1u);
  const json& a = direct[0];
  ASSERT_EQ(a.at("status"), "ok") << a.dump();
  // The direct run's final particles: the last step of its store entry (H5Part), and the same in PySPH's layout.
  const auto [h5part, pysph] = direct_particle_files(work, a);
  json file_base = reduced_cell(32, 12, 0.05);
  const json rows = run_rows(work, "file", "reduced_model", file_base, {{"reference.file", {pysph, h5part}}});
  ASSERT_EQ(rows.size(), 2u);
  expect_file_row(rows[0], pysph, "pysph_output");
  expect_file_row(rows[1], h5part, "h5part");
  EXPECT_EQ(rows[0]["reference_file"]["time"], a["direct_sph"]["time"]);
  // The same particles (the PySPH layout in another order): the averaged reference and every error norm to
  // round-off (the norms are fractions of the peak velocity, 1e-13; v̄_x to 1e-15 absolute, 2e-14 of its peak 0.049).
  for (const json& b : rows) {
    double worst_errors = 0.0, worst_profile = 0.0;
    expect_close(a.at("errors"), b.at("errors"), 1e-13, "errors", &worst_errors);
    expect_close(a.at("profile").at("direct_average"), b.at("profile").at("direct_average"), 1e-15, "direct_average",
                 &worst_profile);
    std::printf("[measured] %s: largest difference from the direct run's row: error norms %.3g, averaged v_x %.3g\n",
                b["reference_file"]["layout"].get<std::string>().c_str(), worst_errors, worst_profile);
  }
}

// PySPH's own file (its peer model of this scene, dumped at t = 0.1) as the reference, against closurelab's direct
// run to t = 0.1: the two codes agree per particle to ~5e-16 of the peak (tests/peer/test_pysph_equivalence.py),
// so the rows' errors agree to round-off of the peak.
TEST(ReducedReferenceFile, APysphWrittenFileGivesTheDirectRunsErrorsAtItsTime) {
  const auto work = fresh_work_folder("reduced_reference_pysph");
  json base = reduced_cell(32, 12, 0.1);
  base["reference"] = {{"solver", {{"mode", "target_time"}, {"target_time", 0.1}}}};
  const auto [direct, file] = direct_and_file_rows(work, base, reduced_cell(32, 12, 0.1), pysph_file, "pysph_output");
  ASSERT_TRUE(direct.contains("errors") && file.contains("errors"));
  EXPECT_EQ(file["reference_file"]["time"], 0.1);
  // v̄_x to 1e-15 absolute: 2e-14 of the peak v_x (0.049) at this time.
  double worst_errors = 0.0, worst_profile = 0.0;
  expect_close(direct.at("errors"), file.at("errors"), 1e-13, "errors", &worst_errors);
  expect_close(direct.at("profile").at("direct_average"), file.at("profile").at("direct_average"), 1e-15,
               "direct_average", &worst_profile);
  std::printf("[measured] PySPH's file vs closurelab's direct run: error norms %.3g, averaged v_x %.3g\n", worst_errors,
              worst_profile);
}

TEST(ReducedReferenceFile, BadFilesAndTransientsAreConfigErrorsBeforeAnythingRuns) {
  const auto work = fresh_work_folder("reduced_reference_bad");
  // The PySPH file's particles, shrunk in y (another box, the same count) or moved out of the box.
  const ParticleSnapshot s = read_particle_snapshot(pysph_file);
  const auto write_csv = [&](const std::string& name, double y_scale, double y_shift) {
    return write_particles_csv(work / name, s.particles, true, 1.0, 0.0, y_scale, y_shift);
  };
  const struct {
    std::string what;
    json reference, transient;
    int n_y;
    std::string path, says;
  } cases[] = {
      {"missing", {{"file", (work / "none.hdf5").string()}}, json::array(), 32, "/reference/file", "not a readable file"},
      {"count", {{"file", pysph_file}}, json::array(), 16, "/reference/file", "particles"},
      {"box", {{"file", write_csv("half.csv", 0.5, 0.0)}}, json::array(), 32, "/reference/file", "another box"},
      {"outside", {{"file", write_csv("out.csv", 1.0, 0.5)}}, json::array(), 32, "/reference/file", "outside"},
      {"transient", {{"file", pysph_file}}, json::array({0.001}), 32, "/transient/t_star", "history"},
      {"solver", {{"file", pysph_file}, {"solver", json::object()}}, json::array(), 32, "/reference/solver", "not used"},
  };
  for (const auto& c : cases) {
    json base = reduced_cell(c.n_y, 12, 0.1);
    base["reference"] = c.reference;
    base["transient"] = {{"t_star", c.transient}};
    expect_refused(work, c.what, base, c.path, c.says);
  }
}
