// reference.file on the 2D force-density model (kind reduced_model, model force_density_2d) on the cylinder lattice
// at n = 32 (a = 0.2 L, η' = L/16: the 16 x 16 coarse mesh), the direct SPH to t = 0.05: (1) the direct run's own
// final particles, the store's H5Part and the same particles rewritten in PySPH's layout (another order), give the
// direct run's averaged field, errors and permeabilities; (2) the file PySPH itself wrote from its peer model of the
// scene (tests/peer/data/cylinders_pysph_n32_t0.05.hdf5: its last dump, poiseuille_pysph_00205.hdf5, from
// `/usr/bin/python3 tests/peer/poiseuille_pysph.py --scene cylinder-lattice --ny 32 --tf 0.05 -d DIR`, PySPH 1.0b1) gives those of
// closurelab's direct run to the same time; (3) bad files are ConfigErrors naming the JSON path before anything runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/base/errors.hpp"
#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "core/io/particle_snapshot.hpp"
#include "experiments/kinds/reference_profiles.hpp"
#include "tests/peer/reference_file_support.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

const std::string pysph_file = std::string(CLOSURELAB_SOURCE_DIR) + "/tests/peer/data/cylinders_pysph_n32_t0.05.hdf5";

// The peer test's cell (tests/peer/test_pysph_equivalence.py --scene cylinder-lattice --ny 32 --tf 0.05).
json cylinder_cell(int n) {
  return {{"model", "force_density_2d"},
          {"scene", {{"name", "cylinder-lattice"}, {"n", n}, {"radius_over_length", 0.2}}},
          {"kernel", {{"name", "gaussian"}}},
          {"timing", {{"min_repeats", 1}, {"max_repeats", 1}}}};
}

json direct_cell() {
  json c = cylinder_cell(32);
  c["reference"] = {{"solver", {{"mode", "target_time"}, {"target_time", 0.05}, {"max_time", 0.05}, {"kappa", 0.25}}}};
  return c;
}

// The rows' errors (vs the averaged reference, permeabilities) and fields within `errors_tol` (fractions of the peak
// speed, and k/L²) and `field_tol` (absolute velocity); the largest differences printed.
void expect_same_reference(const json& direct, const json& file, double errors_tol, double field_tol,
                           const std::string& what) {
  double worst_errors = 0.0, worst_field = 0.0;
  expect_close(direct.at("errors"), file.at("errors"), errors_tol, "errors", &worst_errors);
  expect_close(direct.at("fields").at("direct_average"), file.at("fields").at("direct_average"), field_tol,
               "fields/direct_average", &worst_field);
  const double peak = direct.at("errors").at("scale_peak_speed_of_averaged_direct_sph").get<double>();
  std::printf(
      "[measured] %s: largest difference from the direct run's row: errors %.3g, averaged velocity %.3g "
      "(%.3g of the peak speed %.3g)\n",
      what.c_str(), worst_errors, worst_field, worst_field / peak, peak);
}

}  // namespace

TEST(ReducedReferenceFile2D, TheDirectRunsOwnParticlesGiveItsRow) {
  const auto work = fresh_work_folder("reduced_reference_file_2d");
  const json direct = run_rows(work, "direct", "reduced_model", direct_cell(), json::object());
  ASSERT_EQ(direct.size(), 1u);
  const json& a = direct[0];
  ASSERT_EQ(a.at("status"), "ok") << a.dump();
  ASSERT_TRUE(a.at("errors").at("permeability").contains("direct_sph"));
  const auto [h5part, pysph] = direct_particle_files(work, a);
  json file_base = cylinder_cell(32);
  const json rows = run_rows(work, "file", "reduced_model", file_base, {{"reference.file", {h5part, pysph}}});
  ASSERT_EQ(rows.size(), 2u);
  expect_file_row(rows[0], h5part, "h5part");
  expect_file_row(rows[1], pysph, "pysph_output");
  EXPECT_EQ(rows[0]["reference_file"]["time"], a["direct_sph"]["time"]);
  EXPECT_EQ(rows[1]["reference_file"]["fixed_from"], "file");  // the array named solid
  // The store's particles in the store's order: the same sums in the same order, so the same row, bitwise.
  expect_same_reference(a, rows[0], 0.0, 0.0, "the store's H5Part");
  // PySPH's layout holds the fluid first: the window sums run in another order, round-off of the peak.
  expect_same_reference(a, rows[1], 1e-13, 1e-15, "the same particles in PySPH's layout");
}

// PySPH's dump of its peer model at t = 0.05 against closurelab's direct run to t = 0.05: the two agree per particle
// to 3.2e-12 of the peak velocity (peer.pysph_equivalence_cylinders asserts 1e-10), so the rows agree to that.
TEST(ReducedReferenceFile2D, APysphWrittenFileGivesTheDirectRunsRowAtItsTime) {
  const auto work = fresh_work_folder("reduced_reference_pysph_2d");
  const auto [direct, file] = direct_and_file_rows(work, direct_cell(), cylinder_cell(32), pysph_file, "pysph_output");
  ASSERT_TRUE(direct.contains("errors") && file.contains("errors"));
  EXPECT_DOUBLE_EQ(file["reference_file"]["time"].get<double>(), 0.05);
  const double peak = direct.at("errors").at("scale_peak_speed_of_averaged_direct_sph").get<double>();
  expect_same_reference(direct, file, 1e-10, 1e-10 * peak, "PySPH's own file");
}

TEST(ReducedReferenceFile2D, BadFilesAreConfigErrorsBeforeAnythingRuns) {
  const auto work = fresh_work_folder("reduced_reference_bad_2d");
  // PySPH's particles as CSV without the fixed column (the scene decides), squeezed in x (another box, the same
  // count) or moved out of the box in x.
  const ParticleSnapshot s = read_particle_snapshot(pysph_file);
  const auto write_csv = [&](const std::string& name, double x_scale, double x_shift) {
    return write_particles_csv(work / name, s.particles, false, x_scale, x_shift);
  };
  const struct {
    std::string what;
    json reference;
    int n;
    std::string path, says;
  } cases[] = {
      {"missing", {{"file", (work / "none.hdf5").string()}}, 32, "/reference/file", "not a readable file"},
      {"count", {{"file", pysph_file}}, 48, "/reference/file", "particles"},
      {"box", {{"file", write_csv("narrow.csv", 0.5, 0.0)}}, 32, "/reference/file", "another box"},
      {"outside", {{"file", write_csv("out.csv", 1.0, 0.5)}}, 32, "/reference/file", "outside"},
      {"solver", {{"file", pysph_file}, {"solver", json::object()}}, 32, "/reference/solver", "not used"},
      {"off", {{"file", pysph_file}, {"direct_sph", false}}, 32, "/reference/direct_sph", "asks for none"},
      {"step", {{"step", 0}}, 32, "/reference/step", "no file"},
  };
  for (const auto& c : cases) {
    json base = cylinder_cell(c.n);
    base["reference"] = c.reference;
    expect_refused(work, c.what, base, c.path, c.says);
  }
  // Without the fixed column the scene's solids decide (each particle's nearest lattice site): the flags of
  // PySPH's solid array, particle for particle.
  const auto scene = builtin_registry().scenes.create(cylinder_cell(32).at("scene"), "/scene");
  const ReferenceFile from_csv = read_reference_file(*scene, write_csv("same.csv", 1.0, 0.0), -1, "/reference/file");
  const ReferenceFile from_pysph = read_reference_file(*scene, pysph_file, -1, "/reference/file");
  EXPECT_EQ(from_csv.record.at("fixed_from"), "scene");
  EXPECT_EQ(from_pysph.record.at("fixed_from"), "file");
  ASSERT_EQ(from_csv.particles.size(), from_pysph.particles.size());
  EXPECT_EQ(from_csv.particles.fixed, from_pysph.particles.fixed);
  EXPECT_GT(std::count(from_csv.particles.fixed.begin(), from_csv.particles.fixed.end(), 1), 0);
}

// A file that is not a state of the scene is refused before it scores (each of these scored `ok`: k = 0,
// max_rel 0.0, a negative permeability). Held-fixed flags are compared with the scene's solids (the count and every
// held particle on a site the scene holds); without flags, the file's velocities must agree with the scene's solids
// (held at rest, fluid moving, 1 % of each set may differ); the fluid moves, no particle outruns the sound speed, and
// the Darcy permeability is positive.
TEST(ReducedReferenceFile2D, FilesOfAnotherGeometryOrAtRestAreRefused) {
  const auto work = fresh_work_folder("reduced_reference_geometry_2d");
  const ParticleSnapshot s = read_particle_snapshot(pysph_file);  // a = 0.2 L, n = 32, t = 0.05
  const auto scene_of = [](json scene) { return builtin_registry().scenes.create(scene, "/scene"); };
  json a03 = cylinder_cell(32).at("scene");
  a03["radius_over_length"] = 0.3;
  const auto lattice = scene_of(cylinder_cell(32).at("scene")), lattice_a03 = scene_of(a03);
  const auto channel = scene_of({{"name", "cylinder-channel"}, {"n", 32}, {"radius_over_length", 0.1}});
  const auto refused = [&](const Scene& scene, const std::string& file, const std::string& says) {
    SCOPED_TRACE(file + " for " + scene.name);
    try {
      read_reference_file(scene, file, -1, "/reference/file");
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.path(), "/reference/file");
      EXPECT_NE(e.message().find(says), std::string::npos) << e.message();
    }
  };
  const auto with = [&](const std::function<void(ParticleSystem&)>& change) {
    ParticleSystem p = s.particles;
    change(p);
    return p;
  };
  EXPECT_NO_THROW(read_reference_file(*lattice, pysph_file, -1, "/reference/file"));  // its own scene
  // The 0.2 L file for the 0.3 L scene, with PySPH's solid array and as CSV without flags (the velocities decide).
  refused(*lattice_a03, pysph_file, "not the scene's");
  refused(*lattice_a03, write_particles_csv(work / "a02.csv", s.particles, false), "move in the file");
  // A 0.3 L state for the 0.2 L scene: the 0.3 L lattice, its fluid moving along x at a tenth of the sound speed.
  ParticleSystem a03_state = lattice_a03->make_particles();
  for (std::size_t k = 0; k < a03_state.size(); ++k)
    if (!a03_state.fixed[k]) a03_state.vx[k] = 0.1 * lattice_a03->sound_speed;
  refused(*lattice, write_particles_csv(work / "a03_flags.csv", a03_state, true), "not the scene's");
  refused(*lattice, write_particles_csv(work / "a03.csv", a03_state, false), "exactly at rest");
  // The cylinder lattice's file for the cylinder channel (the same count: walls inside the box).
  refused(*channel, pysph_file, "not the scene's");
  refused(*channel, write_particles_csv(work / "lattice.csv", s.particles, false), "move in the file");
  // PySPH's fluid and solid arrays swapped.
  ParticleSnapshot swapped = s;
  for (auto& f : swapped.particles.fixed) f = f ? 0 : 1;
  write_pysph_layout((work / "swapped.hdf5").string(), swapped);
  refused(*lattice, (work / "swapped.hdf5").string(), "swapped");
  // At rest (a state at t = 0), one particle at 1e160, the flow reversed.
  refused(*lattice, write_particles_csv(work / "rest.csv", with([](ParticleSystem& p) {
                                          std::fill(p.vx.begin(), p.vx.end(), 0.0);
                                          std::fill(p.vy.begin(), p.vy.end(), 0.0);
                                        }), true),
          "at rest");
  refused(*lattice, write_particles_csv(work / "runaway.csv", with([](ParticleSystem& p) {
                                          const auto a = std::find(p.fixed.begin(), p.fixed.end(), 0) - p.fixed.begin();
                                          p.vx[static_cast<std::size_t>(a)] = 1e160;
                                        }), true),
          "faster than the scene's sound speed");
  refused(*lattice, write_particles_csv(work / "reversed.csv", with([](ParticleSystem& p) {
                                          for (auto& v : p.vx) v = -v;
                                        }), true),
          "not positive");
  // Through the command line: refused at validation, the cell's JSON path named, nothing written.
  json base = cylinder_cell(32);
  base["scene"]["radius_over_length"] = 0.3;
  base["reference"] = {{"file", pysph_file}};
  expect_refused(work, "a02_for_a03", base, "/reference/file", "not the scene's");
}
