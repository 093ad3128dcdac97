// The reference store through the command line: a direct SPH reference computed by one spec is reused by
// another spec (same scene, kernel and solver), listed with its size by `closurelab store`, opens in h5py as
// it is, is recomputed after damage, and is computed once when two processes need it at the same time.
#include <gtest/gtest.h>
#include <unistd.h>

#include "core/base/params.hpp"
#include "experiments/kinds/reference_store.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab::testing;
using closurelab::json;
namespace fs = std::filesystem;

namespace {

// A direct_sph_validation spec of a tiny channel (n_y = 16, to t = 0.05: well under a second).
json tiny(const std::string& name) {
  return {{"name", name},
          {"kind", "direct_sph_validation"},
          {"base", {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 16}}},
                    {"solver", {{"mode", "target_time"}, {"target_time", 0.05}}}}}};
}

json run_tiny(const fs::path& work, const std::string& name, const fs::path& store, std::string* err = nullptr) {
  write_text(work / (name + ".spec.json"), tiny(name).dump());
  const CliOutcome o = run_closurelab(work, "run " + (work / (name + ".spec.json")).string() + " --out " +
                                                (work / name).string() + " --store " + store.string());
  EXPECT_EQ(o.code, 0) << o.err;
  if (err) *err = o.err;
  return json::parse(read_text(work / name / (name + ".json"))).at("rows").at(0);
}

}  // namespace

TEST(ReferenceStoreCli, ASecondSpecReusesTheStoredRunAndADamagedEntryIsRecomputed) {
  const auto work = fresh_work_folder("store_cli");
  const fs::path store = work / "store";
  const json first = run_tiny(work, "first", store);
  const json second = run_tiny(work, "second", store);
  EXPECT_FALSE(first["direct_sph"]["reference_store"]["reused"].get<bool>());
  EXPECT_TRUE(second["direct_sph"]["reference_store"]["reused"].get<bool>());
  EXPECT_EQ(second["direct_sph"]["steps"], first["direct_sph"]["steps"]);
  EXPECT_EQ(second["errors"], first["errors"]);  // the same particles
  const std::string id = first["direct_sph"]["reference_store"]["entry"].get<std::string>();

  const CliOutcome list = run_closurelab(work, "store --store " + store.string());
  ASSERT_EQ(list.code, 0) << list.err;
  EXPECT_NE(list.out.find(id), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("poiseuille-uniform (target_time)"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("total 1 entries, "), std::string::npos) << list.out;

  const fs::path payload = store / id / "particles.h5part";
  std::string python;  // one with h5py: python3 on the PATH, else Debian's own
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (python.empty() && run_shell(work, std::string(py) + " -c 'import h5py'").code == 0) python = py;
  if (!python.empty()) {  // opens in h5py as it is
    const CliOutcome py = run_shell(work, python + " -c \"import h5py; f = h5py.File('" + payload.string() +
                                              "', 'r'); s = f['Step#0']; print(len(s['x']), sorted(s.keys()), "
                                              "float(s.attrs['TimeValue']))\"");
    ASSERT_EQ(py.code, 0) << py.err;
    EXPECT_NE(py.out.find("['fixed', 'mass', 'phase', 'vx', 'vy', 'x', 'y', 'z']"), std::string::npos) << py.out;
    EXPECT_EQ(py.out.substr(0, py.out.find(' ')), std::to_string(first["direct_sph"]["total_particles"].get<int>()));
  }

  fs::resize_file(payload, fs::file_size(payload) - 100);  // an interrupted copy, a full disk
  std::string err;
  const json third = run_tiny(work, "third", store, &err);
  EXPECT_NE(err.find("not usable"), std::string::npos) << err;
  EXPECT_FALSE(third["direct_sph"]["reference_store"]["reused"].get<bool>());
  EXPECT_EQ(third["errors"], first["errors"]);  // recomputed: the same result
}

TEST(ReferenceStoreCli, TwoProcessesNeedingTheSameReferenceComputeItOnce) {
  const auto work = fresh_work_folder("store_cli_two");
  const fs::path store = work / "store";
  for (const char* name : {"a", "b"}) write_text(work / (std::string(name) + ".spec.json"), tiny(name).dump());
  const std::string exe = std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab run ";
  const auto cmd = [&](const std::string& n) {
    return exe + (work / (n + ".spec.json")).string() + " --out " + (work / n).string() + " --store " +
           store.string() + " 2>" + (work / (n + ".err")).string();
  };
  ASSERT_EQ(run_shell(work, "(" + cmd("a") + " & " + cmd("b") + "; wait)").code, 0);
  int computed = 0;
  for (const char* n : {"a", "b"}) {
    const json row = json::parse(read_text(work / n / (std::string(n) + ".json")))["rows"][0];
    ASSERT_EQ(row.at("status"), "ok") << read_text(work / (std::string(n) + ".err"));
    computed += row["direct_sph"]["reference_store"]["reused"].get<bool>() ? 0 : 1;
  }
  EXPECT_EQ(computed, 1);
  EXPECT_EQ(closurelab::ReferenceStore(store).list().size(), 1u);
}

// A shared store on a read-only mount: its entries are reused without taking a lock, a missing one is
// computed (not stored) with a note, and the run exits 0. Needs a read-only folder: a private read-only bind
// mount (root with unshare), else the permission bits (a non-root user).
TEST(ReferenceStoreCli, AReadOnlyStoreIsReadWithoutItsLock) {
  const fs::path work = fresh_work_folder("store_read_only"), store = work / "store";
  run_tiny(work, "first", store);
  for (const auto& e : fs::directory_iterator(store))  // a precomputed store copied without its lock files
    if (e.path().extension() == ".lock") fs::remove(e.path());
  std::string wrap;
  if (::geteuid() == 0) {
    if (run_shell(work, "unshare -m true").code != 0) GTEST_SKIP() << "root without unshare: no read-only folder";
    wrap = "unshare -m sh -c 'mount --bind " + store.string() + " " + store.string() + " && mount -o remount,bind,ro " +
           store.string() + " " + store.string() + " && exec \"$0\" \"$@\"' ";
  } else {
    fs::permissions(store, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                    fs::perm_options::remove);
  }
  write_text(work / "second.spec.json", tiny("second").dump());
  json moved = tiny("third");
  moved["base"]["solver"]["target_time"] = 0.04;
  write_text(work / "third.spec.json", moved.dump());
  const auto run = [&](const std::string& name) {
    return run_shell(work, wrap + std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab run " +
                               (work / (name + ".spec.json")).string() + " --out " + (work / name).string() +
                               " --store " + store.string());
  };
  const CliOutcome reuse = run("second");
  EXPECT_EQ(reuse.code, 0) << reuse.err;
  EXPECT_NE(reuse.err.find("read-only"), std::string::npos) << reuse.err;
  const json row = json::parse(read_text(work / "second" / "second.json")).at("rows").at(0);
  EXPECT_TRUE(row.at("direct_sph").at("reference_store").at("reused").get<bool>()) << row.dump();
  const CliOutcome missing = run("third");
  EXPECT_EQ(missing.code, 0) << missing.err;
  EXPECT_NE(missing.err.find("not stored"), std::string::npos) << missing.err;
  fs::permissions(store, fs::perms::owner_write, fs::perm_options::add);
}
