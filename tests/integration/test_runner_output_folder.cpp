// The output folder: a folder the run cannot write is reported before anything is computed; a write error
// during the run stops it cleanly (exit 1, finished cells kept, no abort); a folder in use by another run is
// refused (exit 2) naming the holder.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>

#include "core/base/params.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using namespace closurelab::testing;

namespace {

const char* tiny = R"({"name": "tiny", "kind": "direct_sph_validation",
  "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16}, "solver": {"mode": "target_time", "target_time": 0.02}},
  "axes": {"solver.target_time": [0.02, 0.04]}})";

CliOutcome run_tiny(const fs::path& work, const fs::path& out) {
  write_text(work / "tiny.json", tiny);
  return run_closurelab(work, "run " + (work / "tiny.json").string() + " --out " + out.string());
}

}  // namespace

TEST(RunnerOutputFolder, OutIsAFileIsReportedBeforeComputing) {
  const auto work = fresh_work_folder("out_file");
  write_text(work / "file", "x");
  const CliOutcome o = run_tiny(work, work / "file");
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("--out"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("not a folder"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("started"), std::string::npos) << o.err;
}

TEST(RunnerOutputFolder, CellsIsAFileIsReportedBeforeComputing) {
  const auto work = fresh_work_folder("cells_file");
  write_text(work / "out" / "cells", "x");
  const CliOutcome o = run_tiny(work, work / "out");
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("cells"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("started"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(work / "out" / "tiny.json"));
}

TEST(RunnerOutputFolder, ReadOnlyFolderIsReportedBeforeComputing) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
  const auto work = fresh_work_folder("read_only");
  fs::create_directories(work / "ro");
  fs::permissions(work / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const CliOutcome o = run_tiny(work, work / "ro" / "out");
  fs::permissions(work / "ro", fs::perms::owner_all);
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("not writable"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("started"), std::string::npos) << o.err;
}

TEST(RunnerOutputFolder, AWriteErrorLaterStopsTheRunCleanlyAndKeepsFinishedCells) {
  const auto work = fresh_work_folder("write_error");
  fs::create_directories(work / "out" / "tiny.json");  // the table cannot replace a folder
  const CliOutcome o = run_tiny(work, work / "out");
  EXPECT_EQ(o.code, 1) << o.err;  // not an abort (134)
  EXPECT_NE(o.err.find("tiny.json"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("the run stopped"), std::string::npos) << o.err;
  std::size_t kept = 0;
  for (const auto& e : fs::directory_iterator(work / "out" / "cells")) kept += e.path().extension() == ".json";
  EXPECT_EQ(kept, 1u);  // the first cell is kept; the second was not started
  EXPECT_EQ(o.err.find("cell 2/2"), std::string::npos) << o.err;
  for (const auto& e : fs::recursive_directory_iterator(work / "out"))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();  // no temporary left behind
}

TEST(RunnerOutputFolder, ASecondRunOnALockedFolderSaysWhoHoldsItAndExitsTwo) {
  const auto work = fresh_work_folder("locked");
  fs::create_directories(work / "out");
  const fs::path lock_file = work / "out" / ".closurelab.lock";
  const int fd = ::open(lock_file.c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const std::string note = "pid 4242 on testhost since 2026-01-01T00:00:00Z: closurelab run other.json\n";
  ASSERT_EQ(::write(fd, note.data(), note.size()), static_cast<ssize_t>(note.size()));
  const CliOutcome o = run_tiny(work, work / "out");
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("in use by another run"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("pid 4242 on testhost"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("started"), std::string::npos) << o.err;
  ::close(fd);  // released: the same run now goes through
  const CliOutcome again = run_tiny(work, work / "out");
  EXPECT_EQ(again.code, 0) << again.err;
}
