// PySPH's own output as closurelab input (core/io/pysph_output.hpp). The file tests/peer/data/
// poiseuille_pysph_ny32_t0.1.hdf5 was written by PySPH 1.0b1 itself, running the peer model of the channel
// (tests/peer/poiseuille_pysph.py --ny 32 --tf 0.1; its last dump, as PySPH named it _00410); the CSV beside it
// holds the same particles as PySPH's own loader reads them (tests/peer/data/pysph_to_csv.py, repr: exact).
// No PySPH is needed here: these run in every CI build.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/params.hpp"
#include "core/io/h5part.hpp"
#include "core/io/particle_snapshot.hpp"
#include "core/io/pysph_output.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

const std::string data_dir = std::string(CLOSURELAB_SOURCE_DIR) + "/tests/peer/data/";
const std::string pysph_file = data_dir + "poiseuille_pysph_ny32_t0.1.hdf5";
const std::string csv_file = data_dir + "poiseuille_pysph_ny32_t0.1.csv";

// A minimal file in PySPH's layout with the array `fluid` holding the given properties (all of length 2).
void write_pysph_like(const std::string& file, const std::vector<std::string>& props) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Gclose(H5Gcreate2(f, "solver_data", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5Gclose(H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5Gclose(H5Gcreate2(f, "particles/fluid", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  const hid_t arrays = H5Gcreate2(f, "particles/fluid/arrays", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[1] = {2};
  const double values[2] = {0.25, 0.5};
  for (const std::string& p : props) {
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t set = H5Dcreate2(arrays, p.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
    H5Dclose(set);
    H5Sclose(space);
  }
  H5Gclose(arrays);
  H5Fclose(f);
}

// Every number of `a` equals its counterpart in `b` to 1e-12 relative (integers exactly), the keys the same.
void expect_same_numbers(const json& a, const json& b, const std::string& path) {
  ASSERT_EQ(a.type(), b.type()) << path;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << path;
    for (auto it = a.begin(); it != a.end(); ++it) {
      ASSERT_TRUE(b.contains(it.key())) << path << "/" << it.key();
      expect_same_numbers(it.value(), b.at(it.key()), path + "/" + it.key());
    }
  } else if (a.is_number_float()) {
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_LE(std::abs(x - y), 1e-12 * std::max(std::abs(x), std::abs(y))) << path << ": " << x << " vs " << y;
  } else {
    EXPECT_EQ(a, b) << path;
  }
}

}  // namespace

TEST(PysphOutput, ReadsThePysphFileAsPysphWroteIt) {
  ASSERT_TRUE(is_pysph_output(pysph_file));
  const ParticleSnapshot s = read_particle_snapshot(pysph_file);  // dispatched by the layout, not the extension
  const ParticleSystem& p = s.particles;
  EXPECT_EQ(s.time, 0.1);
  ASSERT_EQ(p.size(), 32u * 12u);
  // The array named `solid` holds the walls: 6 rows each side (3 eta' = 6 eps').
  EXPECT_TRUE(s.has_fixed);
  EXPECT_EQ(std::count(p.fixed.begin(), p.fixed.end(), 1), 2 * 6 * 12);
  for (std::size_t a = 0; a < p.size(); ++a) {
    EXPECT_EQ(p.fixed[a] != 0, p.y[a] < 3.0 / 16.0 || p.y[a] > 13.0 / 16.0) << a;
    if (p.fixed[a]) EXPECT_EQ(p.vx[a], 0.0) << a;
  }
  // The same particles, bit for bit, as PySPH's own loader gives them (the CSV).
  const ParticleSnapshot c = read_particle_snapshot(csv_file);
  ASSERT_EQ(c.particles.size(), p.size());
  EXPECT_EQ(p.x, c.particles.x);
  EXPECT_EQ(p.y, c.particles.y);
  EXPECT_EQ(p.vx, c.particles.vx);
  EXPECT_EQ(p.vy, c.particles.vy);
  EXPECT_EQ(p.mass, c.particles.mass);
  EXPECT_EQ(p.phase, c.particles.phase);
  EXPECT_EQ(p.fixed, c.particles.fixed);
  EXPECT_GT(*std::max_element(p.vx.begin(), p.vx.end()), 0.01);  // a flow, not the rest state
}

TEST(PysphOutput, H5PartFilesStillGoToTheH5PartReader) {
  const auto work = fresh_work_folder("pysph_h5part");
  ParticleSnapshot s;
  s.time = 0.5;
  s.particles.add(0.25, 0.5, 1.0, 0, false);
  s.has_fixed = true;
  const std::string file = (work / "own.hdf5").string();
  write_h5part(file, {s});
  EXPECT_FALSE(is_pysph_output(file));
  EXPECT_FALSE(is_pysph_output(csv_file));
  EXPECT_FALSE(is_pysph_output((work / "missing.hdf5").string()));
  const ParticleSnapshot r = read_particle_snapshot(file);
  EXPECT_EQ(r.time, 0.5);
  ASSERT_EQ(r.particles.size(), 1u);
  EXPECT_TRUE(r.has_fixed);
}

TEST(PysphOutput, MalformedFilesAreRefusedByName) {
  const auto work = fresh_work_folder("pysph_bad");
  const std::string no_u = (work / "no_u.hdf5").string();
  write_pysph_like(no_u, {"x", "y", "v", "m"});
  try {
    read_particle_snapshot(no_u);
    ADD_FAILURE() << "a file without u was read";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/particles/fluid/arrays"), std::string::npos) << what;
    EXPECT_NE(what.find("'u'"), std::string::npos) << what;
  }
  const std::string ok = (work / "ok.hdf5").string();
  write_pysph_like(ok, {"x", "y", "u", "v", "m"});
  const ParticleSnapshot s = read_particle_snapshot(ok, 0);
  EXPECT_FALSE(s.has_fixed);  // only a fluid array: the scene's walls decide
  EXPECT_EQ(s.particles.size(), 2u);
  EXPECT_THROW(read_particle_snapshot(ok, 1), ConfigError);  // one step per PySPH file
  try {
    read_particle_snapshot((work / "run_100.npz").string());
    ADD_FAILURE() << "an npz file was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("pickled"), std::string::npos) << e.what();
  }
}

// The acceptance: a snapshot_closure cell on the PySPH file passes, and gives the row of the same particles from
// the CSV.
TEST(PysphOutput, SnapshotClosureOnAPysphFileEqualsTheCsvOfItsParticles) {
  const auto work = fresh_work_folder("pysph_snapshot_closure");
  const json spec = {
      {"name", "pysph"},
      {"kind", "snapshot_closure"},
      {"base",
       {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 32}, {"n_x", 12}}},
        {"closure", {{"deconvolver", {{"name", "tikhonov"}, {"rule", "gcv"}}}, {"discretization", "coarse_fine"}}}}},
      {"axes", {{"snapshot.file", {pysph_file, csv_file}}}}};
  write_text(work / "spec.json", spec.dump(1));
  const CliOutcome o =
      run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  ASSERT_EQ(o.code, 0) << o.err;
  const json table = json::parse(read_text(work / "out" / "pysph.json"));
  ASSERT_EQ(table.at("rows").size(), 2u);
  for (const json& row : table["rows"]) {
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    EXPECT_EQ(row.at("snapshot").at("particles"), 32 * 12);
    for (const char* part : {"channel", "interior", "wall_band"}) {
      const double v = row["errors"]["stress_xy"][part]["max_rel"].get<double>();
      EXPECT_TRUE(std::isfinite(v)) << part;
      EXPECT_LT(v, 1.0) << part << ": " << row["errors"].dump();  // a closure, not noise
    }
  }
  // The same particles, so the same errors up to the order of the closure's parallel sums, which is not the same
  // from run to run (measured: equal in one run, 4e-14 relative apart in another): 1e-12 relative.
  expect_same_numbers(table["rows"][0]["errors"], table["rows"][1]["errors"], "errors");
}
