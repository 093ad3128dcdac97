// The experiment kind snapshot_closure on particle files written by a small script standing in for another
// SPH code (tests/integration/data/write_lattice_snapshot.py): CSV and H5Part (h5py) are read, averaged,
// deconvolved and closed. Independent check: on a sine profile v_x = sin(2πy) (kolmogorov scene, no walls)
// the averaged field is e·v with e = exp(−(2πη')²/4) (the Gaussian's symbol), the Landweber series of order n
// reconstructs (1 − (1 − e)^{n+1})·v, and the stress (2.13) is linear in the velocities (the pressure part,
// velocity-independent, is the same in both), so the closure's relative stress error is (1 − e)^{n+1}. With
// the coarse nodes on the lattice rows (spacing η'/2 = ε') nothing is interpolated and this holds to rounding.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/params.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab::testing;
using closurelab::json;

namespace {

const std::string script = std::string(CLOSURELAB_SOURCE_DIR) + "/tests/integration/data/write_lattice_snapshot.py";

json run_spec(const std::filesystem::path& work, const json& spec, int expect_code = 0) {
  write_text(work / "spec.json", spec.dump(1));
  const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, expect_code) << o.err;
  return expect_code == 0 ? json::parse(read_text(work / "out" / (spec.at("name").get<std::string>() + ".json"))) : json();
}

// A Python interpreter with h5py ("" when none): python3 on the PATH, else Debian's own (a PATH python3 may
// be another installation without the Debian package python3-h5py).
std::string h5py_python(const std::filesystem::path& work) {
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (run_shell(work, std::string(py) + " -c 'import h5py'").code == 0) return py;
  return "";
}

}  // namespace

TEST(SnapshotClosure, SineSnapshotMatchesTheLandweberPrediction) {
  const auto work = fresh_work_folder("snapshot_sine");
  const std::string csv = (work / "sine.csv").string();
  ASSERT_EQ(run_shell(work, "python3 " + script + " " + csv + " --n-y 32 --n-x 12 --profile sine").code, 0);
  const json spec = {{"name", "sine"},
                     {"kind", "snapshot_closure"},
                     {"base", {{"scene", {{"name", "kolmogorov"}, {"n_y", 32}, {"n_x", 12}}},
                               {"snapshot", {{"file", csv}}},
                               {"closure", {{"deconvolver", {{"name", "landweber"}, {"order", 0}}},
                                            {"spacing_over_eta", 0.5}}}}},
                     {"axes", {{"closure.deconvolver.order", {0, 2}}}}};
  const json table = run_spec(work, spec);
  ASSERT_EQ(table.at("rows").size(), 2u);
  const double e = std::exp(-std::pow(2 * M_PI / 16, 2) / 4);
  for (int k = 0; k < 2; ++k) {
    const json& row = table["rows"][k];
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    EXPECT_EQ(row.at("snapshot").at("particles"), 32 * 12);
    const int order = row["params"]["closure"]["deconvolver"]["order"].get<int>();
    const double predicted = std::pow(1 - e, order + 1);  // 0.0378 (order 0), 5.4e-5 (order 2)
    // Measured: equal to 1e-14; 1e-9 leaves room for the lattice sum of the Gaussian against its integral
    // (aliasing ~exp(−π²(η'/ε')²) = 7e-18) and for summation order.
    EXPECT_NEAR(row["errors"]["stress_xy"]["channel"]["max_rel"].get<double>(), predicted, 1e-9) << order;
    EXPECT_NEAR(row["errors"]["particle_velocity_max_rel"].get<double>(), predicted, 1e-9) << order;
  }
}

TEST(SnapshotClosure, PoiseuilleFromCsvAndFromH5PartGiveTheSameFiniteErrors) {
  const auto work = fresh_work_folder("snapshot_poiseuille");
  const std::string csv = (work / "p.csv").string(), h5 = (work / "p.h5part").string();
  ASSERT_EQ(run_shell(work, "python3 " + script + " " + csv + " --n-y 32 --n-x 12 --profile poiseuille").code, 0);
  const std::string py = h5py_python(work);
  const bool h5py = !py.empty();
  if (h5py) {
    ASSERT_EQ(run_shell(work, py + " " + script + " " + h5 + " --n-y 32 --n-x 12 --profile poiseuille").code, 0);
  }
  json spec = {{"name", "p"},
               {"kind", "snapshot_closure"},
               {"base", {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 32}, {"n_x", 12}}},
                         {"closure", {{"deconvolver", {{"name", "tikhonov"}, {"rule", "gcv"}}},
                                      {"discretization", "coarse_fine"}}}}},
               {"axes", {{"snapshot.file", h5py ? json{csv, h5} : json{csv}}}}};
  const json table = run_spec(work, spec);
  for (const json& row : table.at("rows")) {
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    for (const char* part : {"channel", "interior", "wall_band"}) {
      const double v = row["errors"]["stress_xy"][part]["max_rel"].get<double>();
      EXPECT_TRUE(std::isfinite(v)) << part;
      EXPECT_LT(v, 1.0) << part << ": " << row["errors"].dump();  // a closure, not noise
    }
  }
  if (!h5py) GTEST_SKIP() << "python3-h5py not installed: the H5Part half was not run";
  // The H5Part file carries v_x in single precision: the same errors to float rounding.
  const double a = table["rows"][0]["errors"]["stress_xy"]["channel"]["max_rel"].get<double>();
  const double b = table["rows"][1]["errors"]["stress_xy"]["channel"]["max_rel"].get<double>();
  EXPECT_NEAR(a, b, 1e-5) << a << " vs " << b;
}

TEST(SnapshotClosure, BadFilesAreNamed) {
  const auto work = fresh_work_folder("snapshot_bad");
  json spec = {{"name", "bad"},
               {"kind", "snapshot_closure"},
               {"base", {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 16}}},
                         {"snapshot", {{"file", (work / "missing.csv").string()}}}}}};
  write_text(work / "spec.json", spec.dump());
  CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("/snapshot/file"), std::string::npos) << o.err;
  // A particle outside the scene's box: refused at validation (--dry-run too), the file and the particle named.
  write_text(work / "far.csv", "x,y,vx,vy,mass,phase\n0.1,5.0,0,0,1,0\n");
  spec["base"]["snapshot"]["file"] = (work / "far.csv").string();
  write_text(work / "spec.json", spec.dump());
  o = run_closurelab(work, "run " + (work / "spec.json").string() + " --dry-run");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("/base/snapshot/file"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("outside the scene's box"), std::string::npos) << o.err;
  // A file cut at a line boundary: every line is well formed, but a lattice row's last particle is
  // missing; refused by the particle count, with the file named.
  const std::string whole = (work / "whole.csv").string();
  ASSERT_EQ(run_shell(work, "python3 " + script + " " + whole + " --n-y 16 --n-x 12 --profile poiseuille").code, 0);
  std::string text = read_text(whole);
  text.erase(text.rfind('\n', text.size() - 2) + 1);  // drop the last line, keep its predecessor's newline
  write_text(work / "cut.csv", text);
  spec["base"]["scene"]["n_x"] = 12;
  spec["base"]["snapshot"]["file"] = (work / "cut.csv").string();
  write_text(work / "spec.json", spec.dump());
  o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out3").string());
  EXPECT_EQ(o.code, 2);  // at validation: nothing written
  EXPECT_FALSE(std::filesystem::exists(work / "out3" / "bad.json"));
  EXPECT_NE(o.err.find("cut.csv' holds 191 particles, the scene 'poiseuille-uniform' has 192"), std::string::npos) << o.err;
  // The whole file runs.
  spec["base"]["snapshot"]["file"] = whole;
  write_text(work / "spec.json", spec.dump());
  o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out4").string());
  EXPECT_EQ(o.code, 0) << o.err;
}
