// Readers open regular files only. `seal DIR` read a cell file before the guarded JSON reader, so a FIFO
// named *.json in DIR/cells blocked it for ever and a link to /dev/zero grew its memory to GB; now each is refused
// ("not a regular file"), checked before it is opened, and the other cells are still sealed. `export T.json --csv
// --out T.json` overwrote the table with its CSV (exit 0); now it is refused and the table left as it was.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>

#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using namespace closurelab::testing;

TEST(ReaderGuards, SealRefusesAFifoAndALinkToADeviceWithoutOpeningThem) {
  const auto work = fresh_work_folder("reader_guards_seal");
  const fs::path cells = work / "out" / "cells";
  fs::create_directories(cells);
  ASSERT_EQ(mkfifo((cells / "fifo.json").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", cells / "zero.json");
  const auto t0 = std::chrono::steady_clock::now();
  // `timeout` turns a hang into exit 124 (the test then fails instead of blocking ctest).
  const CliOutcome o = run_shell(work, "timeout 60 " + std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab seal " +
                                           (work / "out").string());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_LT(seconds, 30.0);
  for (const char* name : {"fifo.json", "zero.json"}) {
    const std::string f = (cells / name).string();
    EXPECT_NE(o.err.find("error: " + f + " truncated or unreadable (cannot open '" + f + "': not a regular file)"),
              std::string::npos)
        << o.err;
  }
  EXPECT_NE(o.err.find("0 cell file(s) sealed"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("2 not sealed"), std::string::npos) << o.err;
}

TEST(ReaderGuards, ExportRefusesToWriteOntoItsInput) {
  const auto work = fresh_work_folder("reader_guards_export");
  const std::string table = R"({"experiment": "t", "rows": [{"id": "a", "status": "ok", "params": {"x": 1}}]})";
  write_text(work / "T.json", table);
  fs::create_symlink(work / "T.json", work / "alias.json");
  for (const fs::path& out : {work / "T.json", work / "alias.json", work / "." / "T.json"}) {
    const CliOutcome o = run_closurelab(work, "export " + (work / "T.json").string() + " --csv --out " + out.string());
    EXPECT_EQ(o.code, 2) << out << ": " << o.err;
    EXPECT_NE(o.err.find("would overwrite its input"), std::string::npos) << o.err;
    EXPECT_EQ(read_text(work / "T.json"), table) << out;
  }
  // Another file is written.
  const CliOutcome o = run_closurelab(work, "export " + (work / "T.json").string() + " --csv --out " +
                                                (work / "T.csv").string());
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(read_text(work / "T.csv").find("params.x"), std::string::npos);
}
