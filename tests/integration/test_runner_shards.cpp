// Shards of a matrix (closurelab run --shard i/N) and their merge (closurelab merge DIR): shards 0/2 and 1/2
// into one folder, merged, give the serial table (except timings and provenance); a missing shard is an error
// naming its cells and the command to run; a malformed --shard exits 2 and writes nothing.
// Runs in about 0.5 s (cells of a 16-row channel to t = 0.02..0.04, a few ms each).
#include <gtest/gtest.h>

#include "core/base/params.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/table_compare.hpp"

namespace fs = std::filesystem;
using closurelab::json;
using namespace closurelab::testing;

namespace {

const char* spec = R"({"name": "sharded", "kind": "direct_sph_validation",
  "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16}, "solver": {"mode": "target_time", "target_time": 0.02}},
  "axes": {"solver.target_time": [0.02, 0.04, 0.03], "scene.n_y": [16, 20]}})";

json read(const fs::path& p) { return closurelab::read_json_file(p.string()); }

std::string run_args(const fs::path& work, const fs::path& out) {
  return "run " + (work / "sharded.json").string() + " --out " + out.string();
}

}  // namespace

TEST(RunnerShards, TwoShardsMergedEqualTheSerialTable) {
  const auto work = fresh_work_folder("shards_merge");
  write_text(work / "sharded.json", spec);
  const CliOutcome serial = run_closurelab(work, run_args(work, work / "serial"));
  ASSERT_EQ(serial.code, 0) << serial.err;
  const CliOutcome s0 = run_closurelab(work, run_args(work, work / "out") + " --shard 0/2");
  ASSERT_EQ(s0.code, 0) << s0.err;
  EXPECT_FALSE(fs::exists(work / "out" / "sharded.json")) << "a shard writes no table";
  const CliOutcome s1 = run_closurelab(work, run_args(work, work / "out") + " --shard 1/2");
  ASSERT_EQ(s1.code, 0) << s1.err;
  // The split is cost-balanced: both shards computed cells, 6 in all.
  const json n0 = read(work / "out" / "shards" / "0-of-2.json"), n1 = read(work / "out" / "shards" / "1-of-2.json");
  EXPECT_FALSE(n0.at("cells").empty());
  EXPECT_FALSE(n1.at("cells").empty());
  EXPECT_EQ(n0.at("cells").size() + n1.at("cells").size(), 6u);
  EXPECT_TRUE(n0.at("complete").get<bool>() && n1.at("complete").get<bool>());

  const CliOutcome merged = run_closurelab(work, "merge " + (work / "out").string());
  ASSERT_EQ(merged.code, 0) << merged.err;
  const json a = read(work / "serial" / "sharded.json"), b = read(work / "out" / "sharded.json");
  EXPECT_EQ(without_timings(a), without_timings(b));
  EXPECT_TRUE(b.at("complete").get<bool>());
  EXPECT_EQ(b.at("provenance").at("derived_from"), "rows");
  // A second merge finds the same rows and leaves the table as it is.
  const std::string before = read_text(work / "out" / "sharded.json");
  const CliOutcome again = run_closurelab(work, "merge " + (work / "out").string());
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(read_text(work / "out" / "sharded.json"), before);
}

TEST(RunnerShards, AMissingShardIsAClearErrorAndWritesNoTable) {
  const auto work = fresh_work_folder("shards_missing");
  write_text(work / "sharded.json", spec);
  ASSERT_EQ(run_closurelab(work, run_args(work, work / "out") + " --shard 1/2").code, 0);
  const CliOutcome o = run_closurelab(work, "merge " + (work / "out").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("missing cell"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("of shard 0/2"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("--shard 0/2   (never run)"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("of shard 1/2"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(work / "out" / "sharded.json"));
}

TEST(RunnerShards, MergeOfAFolderWithoutShardsExitsTwo) {
  const auto work = fresh_work_folder("shards_none");
  fs::create_directories(work / "empty");
  const CliOutcome o = run_closurelab(work, "merge " + (work / "empty").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("no shard notes"), std::string::npos) << o.err;
  EXPECT_EQ(run_closurelab(work, "merge").code, 2);
}

TEST(RunnerShards, MalformedShardExitsTwoAndWritesNothing) {
  const auto work = fresh_work_folder("shards_bad");
  write_text(work / "sharded.json", spec);
  for (const char* bad : {"2/2", "1of2", "-1/2", "0/0", "1/", "/2", "a/b", "01/2", "0/2/3", "1 /2", "99999999999/2"}) {
    const CliOutcome o = run_closurelab(work, run_args(work, work / "out") + " --shard '" + bad + "'");
    EXPECT_EQ(o.code, 2) << bad << ": " << o.err;
    EXPECT_NE(o.err.find("--shard"), std::string::npos) << bad << ": " << o.err;
    EXPECT_FALSE(fs::exists(work / "out")) << bad;
  }
  const CliOutcome none = run_closurelab(work, run_args(work, work / "out") + " --shard");
  EXPECT_EQ(none.code, 2) << none.err;
}
