// Reliability at the command line: every command checks its writes, the run's lock is never written through a
// planted link, H5Part steps are found by name, index or time, and a snapshot of huge but finite velocities gives
// finite error norms.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "core/base/params.hpp"
#include "core/io/h5part.hpp"
#include "core/base/errors.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab::testing;
using closurelab::json;
namespace fs = std::filesystem;

namespace {

const std::string bin = std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab";
const std::string script = std::string(CLOSURELAB_SOURCE_DIR) + "/tests/integration/data/write_lattice_snapshot.py";

// A Python interpreter with h5py ("" when none): python3 on the PATH, else Debian's own.
std::string h5py_python(const fs::path& work) {
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (run_shell(work, std::string(py) + " -c 'import h5py'").code == 0) return py;
  return "";
}

std::string tiny_spec() {
  return R"({"name": "tiny", "kind": "direct_sph_validation",
    "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16}, "solver": {"mode": "target_time", "target_time": 0.05}}})";
}

}  // namespace

// Item 6: stdout on /dev/full is an error for list, store, --help, --version and deconvolve (exit 1 and a message),
// as it already was for run. The inner redirection (in a subshell) overrides run_shell's capture.
TEST(CliReliability, CommandsWithStdoutOnAFullDeviceExitNonZero) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const fs::path work = fresh_work_folder("cli_full");
  write_text(work / "A.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n0\n0\n1\n");
  write_text(work / "b.mtx", "%%MatrixMarket matrix array real general\n2 1\n1\n2\n");
  const std::string deconvolve =
      "deconvolve --matrix " + (work / "A.mtx").string() + " --rhs " + (work / "b.mtx").string() + " --method cgls";
  for (const std::string& args : {std::string("list"), std::string("list deconvolver"),
                                 "store --store " + (work / "store").string(), std::string("--help"),
                                 std::string("--version"), deconvolve}) {
    SCOPED_TRACE(args);
    const CliOutcome ok = run_closurelab(work, args);
    ASSERT_EQ(ok.code, 0) << ok.err;
    const CliOutcome full = run_shell(work, "( " + bin + " " + args + " >/dev/full )");
    EXPECT_EQ(full.code, 1) << full.err;
    EXPECT_NE(full.err.find("standard output"), std::string::npos) << full.err;
  }
  // --out on a full device: exit 1, the file named, nothing left that looks like a solution.
  const CliOutcome out = run_closurelab(work, deconvolve + " --out /dev/full");
  EXPECT_EQ(out.code, 1) << out.err;
  EXPECT_NE(out.err.find("/dev/full"), std::string::npos) << out.err;
}

// Item 7: a symbolic link planted at DIR/.closurelab.lock is not followed: the run refuses (exit 2) and the
// link's target keeps its content.
TEST(CliReliability, APlantedLockLinkIsNotFollowed) {
  const fs::path work = fresh_work_folder("cli_lock_link");
  write_text(work / "spec.json", tiny_spec());
  write_text(work / "precious.txt", "do not overwrite\n");
  fs::create_directories(work / "out");
  fs::create_symlink(work / "precious.txt", work / "out" / ".closurelab.lock");
  const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("symbolic link"), std::string::npos) << o.err;
  EXPECT_EQ(read_text(work / "precious.txt"), "do not overwrite\n");
  EXPECT_FALSE(fs::exists(work / "out" / "tiny.json"));
}

// Item 2: a file with the groups Step#0 (t = 0), Step#10 (t = 0.1), Step#20 (t = 0.2), as codes that write every
// 10th step produce. The last step is Step#20 (not Step#0); steps are found by number, by place and by time,
// and what does not exist, or is ambiguous, is refused with the steps the file has.
TEST(CliReliability, H5PartStepsAreFoundByNameIndexAndTime) {
  const fs::path work = fresh_work_folder("cli_h5part_steps");
  const std::string py = h5py_python(work);
  if (py.empty()) GTEST_SKIP() << "python3-h5py not installed";
  const std::string f = (work / "steps.h5part").string();
  const std::string writer =
      "import h5py, numpy as np\n"
      "with h5py.File('" + f + "', 'w') as h:\n"
      "  for n, t, v in [(0, 0.0, 0.0), (10, 0.1, 1.0), (20, 0.2, 2.0)]:\n"
      "    g = h.create_group('Step#%d' % n)\n"
      "    g.attrs['TimeValue'] = t\n"
      "    g['x'] = np.array([0.25, 0.75]); g['y'] = np.array([0.5, 0.5]); g['z'] = np.zeros(2)\n"
      "    g['vx'] = np.array([v, v]); g['vy'] = np.zeros(2); g['mass'] = np.ones(2)\n"
      "  h.create_group('Step#x')\n";  // not a step: ignored
  write_text(work / "w.py", writer);
  ASSERT_EQ(run_shell(work, py + " " + (work / "w.py").string()).code, 0);
  using namespace closurelab;
  const auto steps = h5part_steps(f);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[2].group, "Step#20");
  EXPECT_DOUBLE_EQ(steps[1].time, 0.1);
  EXPECT_EQ(h5part_step_count(f), 3);
  EXPECT_DOUBLE_EQ(read_h5part(f, -1).particles.vx[0], 2.0);  // the last: Step#20
  EXPECT_DOUBLE_EQ(read_h5part(f, 20).particles.vx[0], 2.0);
  EXPECT_DOUBLE_EQ(read_h5part(f, 10).time, 0.1);
  EXPECT_EQ(h5part_select_step(f, H5PartStepBy::index, 1), 10);
  EXPECT_EQ(h5part_select_step(f, H5PartStepBy::index, -1), 20);
  EXPECT_EQ(h5part_select_step(f, H5PartStepBy::time, 0, 0.2), 20);
  EXPECT_EQ(h5part_select_step(f, H5PartStepBy::time, 0, 0.0), 0);
  for (auto bad : {std::function<void()>([&] { read_h5part(f, 2); }),
                   std::function<void()>([&] { h5part_select_step(f, H5PartStepBy::index, 3); }),
                   std::function<void()>([&] { h5part_select_step(f, H5PartStepBy::time, 0, 0.15); })}) {
    try {
      bad();
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("Step#0 (t = 0), Step#10 (t = 0.1), Step#20 (t = 0.2)"), std::string::npos) << m;
    }
  }
  // Two groups naming one step: ambiguous.
  write_text(work / "w2.py", "import h5py\nh = h5py.File('" + f + "', 'a')\nh.copy('Step#10', 'Step#010')\nh.close()\n");
  ASSERT_EQ(run_shell(work, py + " " + (work / "w2.py").string()).code, 0);
  try {
    read_h5part(f, -1);
    ADD_FAILURE() << "accepted Step#10 and Step#010";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("ambiguous"), std::string::npos) << e.what();
  }
}

// Item 2 through a spec: step_by index and time, and the refusals at validation.
TEST(CliReliability, SnapshotSpecPicksTheStepByIndexOrTime) {
  const fs::path work = fresh_work_folder("cli_h5part_spec");
  const std::string py = h5py_python(work);
  if (py.empty()) GTEST_SKIP() << "python3-h5py not installed";
  const std::string one = (work / "one.h5part").string(), f = (work / "s.h5part").string();
  ASSERT_EQ(run_shell(work, py + " " + script + " " + one + " --n-y 16 --n-x 12 --profile poiseuille").code, 0);
  // Step#0 at rest (t = 0) and Step#10 (the flow), as a code writing every 10th step leaves them.
  write_text(work / "w.py", "import h5py\nh = h5py.File('" + f + "', 'w')\ns = h5py.File('" + one +
                                "', 'r')\ns.copy('Step#0', h, 'Step#10')\nh['Step#10'].attrs['TimeValue'] = 0.5\n"
                                "s.copy('Step#0', h, 'Step#0')\nh['Step#0']['vx'][...] = 0\nh.close()\n");
  ASSERT_EQ(run_shell(work, py + " " + (work / "w.py").string()).code, 0);
  auto spec = [&](const json& snapshot) {
    return json{{"name", "s"},
                {"kind", "snapshot_closure"},
                {"base", {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 16}, {"n_x", 12}}}, {"snapshot", snapshot}}}};
  };
  auto run = [&](const json& snapshot, const std::string& out) {
    write_text(work / (out + ".json"), spec(snapshot).dump());
    return run_closurelab(work, "run " + (work / (out + ".json")).string() + " --out " + (work / out).string());
  };
  for (const json& pick : {json{{"file", f}}, json{{"file", f}, {"step", 10}}, json{{"file", f}, {"step", 1}, {"step_by", "index"}},
                           json{{"file", f}, {"time", 0.5}, {"step_by", "time"}}}) {
    SCOPED_TRACE(pick.dump());
    const CliOutcome o = run(pick, "ok");
    ASSERT_EQ(o.code, 0) << o.err;
    const json table = json::parse(read_text(work / "ok" / "s.json"));
    EXPECT_EQ(table["rows"][0]["snapshot"]["time"], 0.5);  // Step#10, not the fluid at rest
    EXPECT_EQ(table["rows"][0]["status"], "ok");
    fs::remove_all(work / "ok");
  }
  CliOutcome o = run({{"file", f}, {"step", 2}}, "bad1");
  EXPECT_EQ(o.code, 2) << o.err;  // refused at validation with the steps listed (the file is read there)
  EXPECT_NE(o.err.find("there is no Step#2"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("/base/snapshot/file"), std::string::npos) << o.err;
  o = run({{"file", f}, {"time", 0.5}}, "bad2");
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("/snapshot/time"), std::string::npos) << o.err;
  o = run({{"file", f}, {"time", 0.5}, {"step", 10}, {"step_by", "time"}}, "bad3");
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("ambiguous"), std::string::npos) << o.err;
}

// Item 1: velocities of 1e154 and 1e200 in a CSV snapshot (finite) give finite error norms with l2_rel > 0 where
// max_rel > 0 (before: l2_rel = 0 at 1e154, null at 1e200, both `ok`).
TEST(CliReliability, HugeFiniteSnapshotVelocitiesGiveFiniteNorms) {
  const fs::path work = fresh_work_folder("cli_huge_snapshot");
  const std::string csv = (work / "p.csv").string();
  ASSERT_EQ(run_shell(work, "python3 " + script + " " + csv + " --n-y 16 --n-x 12 --profile poiseuille").code, 0);
  for (const char* scale : {"1e154", "1e200"}) {
    SCOPED_TRACE(scale);
    const std::string big = (work / (std::string("big") + scale + ".csv")).string();
    write_text(work / "scale.py", std::string("import sys\nlines = open('") + csv + "').read().splitlines()\n"
                                  "out = [lines[0]]\nfor l in lines[1:]:\n  c = l.split(',')\n  c[2] = repr(float(c[2]) * " +
                                  scale + ")\n  out.append(','.join(c))\nopen('" + big + "', 'w').write('\\n'.join(out) + '\\n')\n");
    ASSERT_EQ(run_shell(work, "python3 " + (work / "scale.py").string()).code, 0);
    const json spec = {{"name", "h"},
                       {"kind", "snapshot_closure"},
                       {"base", {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 16}, {"n_x", 12}}},
                                 {"snapshot", {{"file", big}}},
                                 {"closure", {{"deconvolver", {{"name", "landweber"}, {"order", 1}}}}}}}};
    write_text(work / "spec.json", spec.dump());
    fs::remove_all(work / "out");
    const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
    const json row = json::parse(read_text(work / "out" / "h.json"))["rows"][0];
    for (const char* part : {"channel", "interior", "wall_band"}) {
      const json& e = row["errors"]["stress_xy"][part];
      ASSERT_TRUE(e["l2_rel"].is_number()) << row["errors"].dump();
      const double l2 = e["l2_rel"].get<double>(), mx = e["max_rel"].get<double>();
      EXPECT_TRUE(std::isfinite(l2) && std::isfinite(mx)) << part;
      if (mx > 0) {
        EXPECT_GT(l2, 0.0) << part << ": " << e.dump();
      }
    }
    if (row["status"] == "ok") {
      EXPECT_EQ(o.code, 0);
    }
  }
}

// Smaller items (HDF5): a file declaring 1e12 particles was a bare std::bad_alloc; a phase of 0.5 was read as 0
// and a uint64 of 2^63 as 2147483647. Now: refused with the file, step and dataset named.
TEST(CliReliability, H5PartDeclaredSizesAndPhasesAreChecked) {
  const fs::path work = fresh_work_folder("cli_h5part_checks");
  const std::string py = h5py_python(work);
  if (py.empty()) GTEST_SKIP() << "python3-h5py not installed";
  auto write = [&](const std::string& file, const std::string& body) {
    write_text(work / "w.py", "import h5py, numpy as np\nwith h5py.File('" + (work / file).string() +
                                  "', 'w') as h:\n  g = h.create_group('Step#0')\n" + body);
    ASSERT_EQ(run_shell(work, py + " " + (work / "w.py").string()).code, 0);
  };
  const std::string two = "  for k in ['x', 'y', 'vx', 'vy', 'mass']: g[k] = np.array([0.5, 1.0])\n";
  write("huge.h5part", "  g.create_dataset('x', shape=(10**12,), dtype='f8', chunks=(1024,))\n");
  write("half.h5part", two + "  g['phase'] = np.array([0.0, 0.5])\n");
  write("big.h5part", two + "  g['phase'] = np.array([0, 2**63], dtype=np.uint64)\n");
  write("ok.h5part", two + "  g['phase'] = np.array([0, 3], dtype=np.int64)\n");
  using namespace closurelab;
  auto refusal = [&](const std::string& file) {
    try {
      read_h5part((work / file).string());
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::string m = refusal("huge.h5part");
  EXPECT_NE(m.find("Step#0/x"), std::string::npos) << m;
  EXPECT_NE(m.find("memory limit"), std::string::npos) << m;
  m = refusal("half.h5part");
  EXPECT_NE(m.find("Step#0/phase: entry 1 = 0.5"), std::string::npos) << m;
  m = refusal("big.h5part");
  EXPECT_NE(m.find("Step#0/phase: entry 1"), std::string::npos) << m;
  const ParticleSnapshot s = read_h5part((work / "ok.h5part").string());
  ASSERT_EQ(s.particles.phase.size(), 2u);
  EXPECT_EQ(s.particles.phase[1], 3);
}
