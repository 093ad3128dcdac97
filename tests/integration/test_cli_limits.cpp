// Reliability limits at the command line: one lock per output folder for plain and sharded runs, the memory and
// cell limits configurable and refused before anything is allocated.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/support/cli_run.hpp"

using namespace closurelab::testing;
namespace fs = std::filesystem;

namespace {

std::string tiny_spec() {
  return R"({"name": "tiny", "kind": "direct_sph_validation",
    "axes": {"scene.n_y": [16, 20]},
    "base": {"scene": {"name": "poiseuille-uniform"}, "solver": {"mode": "target_time", "target_time": 0.05}}})";
}

// Holds DIR/.closurelab.lock as another process would (shared: a shard; exclusive: a plain run, merge or seal).
struct HeldLock {
  int fd = -1;
  HeldLock(const fs::path& file, int how, const std::string& note = "") {
    fd = ::open(file.c_str(), O_RDWR | O_CREAT, 0644);
    if (fd >= 0 && ::flock(fd, how | LOCK_NB) != 0) {
      ::close(fd);
      fd = -1;
    }
    if (fd >= 0 && !note.empty() && ::write(fd, note.data(), note.size()) < 0) {
    }
  }
  ~HeldLock() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

// A plain run on a folder where a shard computes (the folder's lock held shared) exits 2 and computes nothing.
TEST(CliLimits, APlainRunOnAFolderWhereShardsRunExitsTwo) {
  const fs::path work = fresh_work_folder("lock_plain_vs_shard");
  write_text(work / "spec.json", tiny_spec());
  fs::create_directories(work / "out");
  const HeldLock shard(work / "out" / ".closurelab.lock", LOCK_SH);
  ASSERT_GE(shard.fd, 0);
  const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("in use by another run"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("shards of a run"), std::string::npos) << o.err;
  EXPECT_TRUE(fs::is_empty(work / "out" / "cells")) << "a cell was computed";
}

// A shard on a folder where a plain run computes (the folder's lock held exclusively) exits 2 naming the holder;
// shards share the folder with each other (one shard's lock held shared: another shard runs and writes its cells),
// and the same shard twice is refused.
TEST(CliLimits, AShardRunOnAFolderWhereAPlainRunRunsExitsTwo) {
  const fs::path work = fresh_work_folder("lock_shard_vs_plain");
  write_text(work / "spec.json", tiny_spec());
  fs::create_directories(work / "out");
  const std::string shard0 = "run " + (work / "spec.json").string() + " --out " + (work / "out").string() + " --shard 0/2";
  {
    const HeldLock plain(work / "out" / ".closurelab.lock", LOCK_EX, "pid 4242 on testhost: closurelab run other.json\n");
    ASSERT_GE(plain.fd, 0);
    const CliOutcome o = run_closurelab(work, shard0);
    EXPECT_EQ(o.code, 2) << o.err;
    EXPECT_NE(o.err.find("pid 4242 on testhost"), std::string::npos) << o.err;
    EXPECT_TRUE(!fs::exists(work / "out" / "cells") || fs::is_empty(work / "out" / "cells"));
  }
  {
    const HeldLock other_shard(work / "out" / ".closurelab.lock", LOCK_SH);
    ASSERT_GE(other_shard.fd, 0);
    const HeldLock same_shard(work / "out" / ".closurelab.shard-0-of-2.lock", LOCK_EX);
    ASSERT_GE(same_shard.fd, 0);
    const CliOutcome twice = run_closurelab(work, shard0);
    EXPECT_EQ(twice.code, 2) << twice.err;
  }
  const HeldLock other_shard(work / "out" / ".closurelab.lock", LOCK_SH);
  ASSERT_GE(other_shard.fd, 0);
  const CliOutcome o = run_closurelab(work, shard0);
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_FALSE(fs::is_empty(work / "out" / "cells"));
}

// --memory-limit lowers the limit every estimate is checked against, and names itself in the message.
TEST(CliLimits, TheMemoryLimitIsConfigurable) {
  const fs::path work = fresh_work_folder("memory_limit_flag");
  write_text(work / "spec.json", tiny_spec());
  const CliOutcome fits = run_closurelab(work, "run " + (work / "spec.json").string() + " --dry-run");
  EXPECT_EQ(fits.code, 0) << fits.err;
  const CliOutcome low = run_closurelab(work, "run " + (work / "spec.json").string() + " --dry-run --memory-limit 100kB");
  EXPECT_EQ(low.code, 2) << low.err;
  EXPECT_NE(low.err.find("memory limit of 100.0 kB (--memory-limit)"), std::string::npos) << low.err;
  const CliOutcome bad = run_closurelab(work, "run " + (work / "spec.json").string() + " --dry-run --memory-limit 8 parsecs");
  EXPECT_EQ(bad.code, 2) << bad.err;
  const CliOutcome env = run_shell(work, "CLOSURELAB_MEMORY_LIMIT=100kB " + std::string(CLOSURELAB_BINARY_DIR) +
                                             "/experiments/closurelab run " + (work / "spec.json").string() + " --dry-run");
  EXPECT_EQ(env.code, 2) << env.err;
  EXPECT_NE(env.err.find("(CLOSURELAB_MEMORY_LIMIT)"), std::string::npos) << env.err;
}

// The cell limit: counted before the matrix is expanded; --max-cells lowers or raises it.
TEST(CliLimits, TheCellLimitIsConfigurable) {
  const fs::path work = fresh_work_folder("max_cells_flag");
  write_text(work / "spec.json", tiny_spec());
  const CliOutcome one = run_closurelab(work, "run " + (work / "spec.json").string() + " --dry-run --max-cells 1");
  EXPECT_EQ(one.code, 2) << one.err;
  EXPECT_NE(one.err.find("/axes: the matrix has 2 cells (2), above the cell limit of 1 (--max-cells)"), std::string::npos)
      << one.err;
  const CliOutcome two = run_closurelab(work, "run " + (work / "spec.json").string() + " --dry-run --max-cells 2");
  EXPECT_EQ(two.code, 0) << two.err;
}
