// A reduced_model cell whose reference is a particle file (reference.file, experiments/kinds/reference_profiles.hpp)
// instead of the direct SPH run: (1) the direct run's own final particles, written in PySPH's HDF5 layout and
// taken as the store's H5Part, give the direct run's errors; (2) the file PySPH itself wrote
// (tests/peer/data/poiseuille_pysph_ny32_t0.1.hdf5, PySPH 1.0b1, t = 0.1) gives the errors of closurelab's direct
// run to the same time; (3) bad files and a file with transient snapshots are ConfigErrors before anything runs.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>

#include "core/base/params.hpp"
#include "core/io/particle_snapshot.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

const std::string pysph_file = std::string(CLOSURELAB_SOURCE_DIR) + "/tests/peer/data/poiseuille_pysph_ny32_t0.1.hdf5";

void write_array(hid_t group, const char* name, const std::vector<double>& v) {
  const hsize_t dims[1] = {v.size()};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t set = H5Dcreate2(group, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(set);
  H5Sclose(space);
}

// `s` as PySPH's HDFOutput writes a dump: /solver_data (attribute t), /particles/{fluid,solid}/arrays/{x,y,u,v,m}
// with the held-fixed particles in `solid` (the order changes: fluid first, then solid).
void write_pysph_layout(const std::string& file, const ParticleSnapshot& s) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t solver = H5Gcreate2(f, "solver_data", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t t = H5Acreate2(solver, "t", H5T_IEEE_F64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(t, H5T_NATIVE_DOUBLE, &s.time);
  H5Aclose(t);
  H5Sclose(scalar);
  H5Gclose(solver);
  H5Gclose(H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  const ParticleSystem& p = s.particles;
  for (const int fixed : {0, 1}) {
    const std::string name = std::string("particles/") + (fixed ? "solid" : "fluid");
    H5Gclose(H5Gcreate2(f, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    const hid_t arrays = H5Gcreate2(f, (name + "/arrays").c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<double> x, y, u, v, m;
    for (std::size_t a = 0; a < p.size(); ++a)
      if ((p.fixed[a] != 0) == (fixed != 0)) {
        x.push_back(p.x[a]), y.push_back(p.y[a]), u.push_back(p.vx[a]), v.push_back(p.vy[a]), m.push_back(p.mass[a]);
      }
    write_array(arrays, "x", x), write_array(arrays, "y", y), write_array(arrays, "u", u);
    write_array(arrays, "v", v), write_array(arrays, "m", m);
    H5Gclose(arrays);
  }
  H5Fclose(f);
}

// Every number of `a` within `tol` (absolute: the error norms are fractions of the peak velocity) of `b`.
void expect_close(const json& a, const json& b, double tol, const std::string& path, double* worst) {
  ASSERT_EQ(a.type(), b.type()) << path;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << path;
    for (auto it = a.begin(); it != a.end(); ++it) {
      ASSERT_TRUE(b.contains(it.key())) << path << "/" << it.key();
      expect_close(it.value(), b.at(it.key()), tol, path + "/" + it.key(), worst);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << path;
    for (std::size_t k = 0; k < a.size(); ++k) expect_close(a[k], b[k], tol, path + "/" + std::to_string(k), worst);
  } else if (a.is_number()) {
    const double d = std::abs(a.get<double>() - b.get<double>());
    *worst = std::max(*worst, d);
    EXPECT_LE(d, tol) << path << ": " << a << " vs " << b;
  } else {
    EXPECT_EQ(a, b) << path;
  }
}

json reduced_cell(int n_y, int n_x, double t_end) {
  return {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", n_y}, {"n_x", n_x}}},
          {"quadrature", {{"name", "coarse"}, {"stride_y", 2}}},
          {"solver", {{"mode", "target_time"}, {"target_time", t_end}, {"scheme", "staggered"}}}};
}

json run_rows(const std::filesystem::path& work, const std::string& name, const json& base, const json& axes) {
  const json spec = {{"name", name}, {"kind", "reduced_model"}, {"base", base}, {"axes", axes}};
  write_text(work / (name + ".json"), spec.dump(1));
  const CliOutcome o = run_closurelab(work, "run " + (work / (name + ".json")).string() + " --out " +
                                                (work / name).string() + " --store " + (work / "store").string());
  EXPECT_EQ(o.code, 0) << o.err;
  if (o.code != 0) return json::array();
  return json::parse(read_text(work / name / (name + ".json"))).at("rows");
}

void expect_file_row(const json& row, const std::string& file, const std::string& layout) {
  ASSERT_EQ(row.at("status"), "ok") << row.dump();
  EXPECT_FALSE(row.contains("direct_sph"));
  const json& r = row.at("reference_file");
  EXPECT_EQ(r.at("path"), file);
  EXPECT_EQ(r.at("bytes").get<std::uintmax_t>(), std::filesystem::file_size(file));
  EXPECT_EQ(r.at("fnv1a64").get<std::string>().size(), 16u);
  EXPECT_EQ(r.at("layout"), layout);
  EXPECT_TRUE(row.at("cost").at("speed_up").is_null());  // no direct run timed: no speed-up, not 0
  EXPECT_TRUE(row.at("cost").contains("speed_up_note"));
  EXPECT_FALSE(row.at("cost").contains("direct_sph_wall_seconds"));
}

}  // namespace

TEST(ReducedReferenceFile, TheDirectRunsOwnParticlesGiveItsErrors) {
  const auto work = fresh_work_folder("reduced_reference_file");
  json base = reduced_cell(32, 12, 0.05);
  base["reference"] = {{"solver", {{"mode", "target_time"}, {"target_time", 0.05}}}};
  const json direct = run_rows(work, "direct", base, json::object());
  ASSERT_EQ(direct.size(), 1u);
  const json& a = direct[0];
  ASSERT_EQ(a.at("status"), "ok") << a.dump();
  // The direct run's final particles: the last step of its store entry (H5Part), and the same in PySPH's layout.
  const std::string h5part =
      (work / "store" / a.at("direct_sph").at("reference_store").at("entry").get<std::string>() / "particles.h5part")
          .string();
  const ParticleSnapshot last = read_particle_snapshot(h5part, -1);
  const std::string pysph = (work / "direct_final.hdf5").string();
  write_pysph_layout(pysph, last);
  json file_base = reduced_cell(32, 12, 0.05);
  const json rows = run_rows(work, "file", file_base, {{"reference.file", {pysph, h5part}}});
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
  const json direct = run_rows(work, "direct", base, json::object());
  json file_base = reduced_cell(32, 12, 0.1);
  file_base["reference"] = {{"file", pysph_file}};
  const json file = run_rows(work, "file", file_base, json::object());
  ASSERT_EQ(direct.size(), 1u);
  ASSERT_EQ(file.size(), 1u);
  ASSERT_EQ(direct[0].at("status"), "ok") << direct[0].dump();
  expect_file_row(file[0], pysph_file, "pysph_output");
  EXPECT_EQ(file[0]["reference_file"]["time"], 0.1);
  EXPECT_EQ(file[0]["reference_file"]["fixed_from"], "file");  // the array named solid
  // v̄_x to 1e-15 absolute: 2e-14 of the peak v_x (0.049) at this time.
  double worst_errors = 0.0, worst_profile = 0.0;
  expect_close(direct[0].at("errors"), file[0].at("errors"), 1e-13, "errors", &worst_errors);
  expect_close(direct[0].at("profile").at("direct_average"), file[0].at("profile").at("direct_average"), 1e-15,
               "direct_average", &worst_profile);
  std::printf("[measured] PySPH's file vs closurelab's direct run: error norms %.3g, averaged v_x %.3g\n", worst_errors,
              worst_profile);
}

TEST(ReducedReferenceFile, BadFilesAndTransientsAreConfigErrorsBeforeAnythingRuns) {
  const auto work = fresh_work_folder("reduced_reference_bad");
  // The PySPH file's particles, shrunk in y (another box, the same count) or moved out of the box.
  const ParticleSnapshot s = read_particle_snapshot(pysph_file);
  const auto write_csv = [&](const std::string& name, double y_scale, double y_shift) {
    std::string text = "x,y,vx,vy,mass,phase,fixed\n";
    const ParticleSystem& p = s.particles;
    for (std::size_t a = 0; a < p.size(); ++a)
      text += std::to_string(p.x[a]) + "," + std::to_string(p.y[a] * y_scale + y_shift) + "," + std::to_string(p.vx[a]) +
              ",0," + std::to_string(p.mass[a]) + ",0," + std::to_string(p.fixed[a]) + "\n";
    write_text(work / name, text);
    return (work / name).string();
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
    const json spec = {{"name", c.what}, {"kind", "reduced_model"}, {"base", base}};
    write_text(work / (c.what + ".json"), spec.dump(1));
    const CliOutcome o = run_closurelab(work, "run " + (work / (c.what + ".json")).string() + " --out " +
                                                  (work / c.what).string() + " --store " + (work / "store").string());
    EXPECT_EQ(o.code, 2) << c.what << ": " << o.err;
    EXPECT_NE(o.err.find(c.path), std::string::npos) << c.what << ": " << o.err;
    EXPECT_NE(o.err.find(c.says), std::string::npos) << c.what << ": " << o.err;
    EXPECT_FALSE(std::filesystem::exists(work / c.what / (c.what + ".json"))) << c.what << ": a table was written";
  }
}
