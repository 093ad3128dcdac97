// The checksum of a cell file (DIR/cells/<id>.json, results_table.hpp): a run writes it; a resumed run recomputes a
// cell whose file was edited by hand or is truncated, saying so and naming the file; `merge` refuses such a cell
// ("does not match its checksum" / "truncated or unreadable: FILE", never "missing") and writes no table; a cell
// file without a checksum (an older closurelab, the committed results) is still reused and merged, with a note.
// Runs in about 1 s (cells of a 16-row channel to t = 0.02..0.04, a few ms each).
#include <gtest/gtest.h>

#include "core/base/params.hpp"
#include "experiments/runner/results_table.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using closurelab::json;
using namespace closurelab::testing;

namespace {

const char* spec = R"({"name": "summed", "kind": "direct_sph_validation",
  "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16}, "solver": {"mode": "target_time", "target_time": 0.02}},
  "axes": {"solver.target_time": [0.02, 0.04], "scene.n_y": [16, 20]}})";

json read(const fs::path& p) { return closurelab::read_json_file(p.string()); }

std::string run_args(const fs::path& work) {
  return "run " + (work / "summed.json").string() + " --out " + (work / "out").string();
}

fs::path first_cell(const fs::path& work) {
  return work / "out" / "cells" / (read(work / "out" / "summed.json")["rows"][0]["id"].get<std::string>() + ".json");
}

// Runs the two shards of the spec into work/out (no table).
void run_shards(const fs::path& work) {
  for (const char* s : {" --shard 0/2", " --shard 1/2"}) ASSERT_EQ(run_closurelab(work, run_args(work) + s).code, 0);
}

fs::path any_cell(const fs::path& work) {
  for (const auto& e : fs::directory_iterator(work / "out" / "cells")) return e.path();
  return {};
}

}  // namespace

TEST(RunnerCellChecksum, EveryCellFileCarriesTheChecksumOfItsRowAndTheTableDoesNot) {
  const auto work = fresh_work_folder("cell_checksum_written");
  write_text(work / "summed.json", spec);
  ASSERT_EQ(run_closurelab(work, run_args(work)).code, 0);
  const json table = read(work / "out" / "summed.json");
  for (const json& row : table["rows"]) {
    EXPECT_FALSE(row.contains(closurelab::cell_checksum_key));
    json stored = read(work / "out" / "cells" / (row["id"].get<std::string>() + ".json"));
    ASSERT_TRUE(stored.contains(closurelab::cell_checksum_key));
    EXPECT_EQ(stored[closurelab::cell_checksum_key], closurelab::cell_checksum(row));
    stored.erase(closurelab::cell_checksum_key);
    EXPECT_EQ(stored, row);
  }
}

TEST(RunnerCellChecksum, AResumedRunRecomputesAnEditedOrTruncatedCellAndNamesItsFile) {
  const auto work = fresh_work_folder("cell_checksum_resume");
  write_text(work / "summed.json", spec);
  ASSERT_EQ(run_closurelab(work, run_args(work)).code, 0);
  const json before = read(work / "out" / "summed.json");
  const fs::path cell = first_cell(work);
  // A hand edit with the id and parameters kept: the checksum no longer matches.
  json edited = read(cell);
  edited["cell_wall_seconds"] = 1234.5;
  write_text(cell, edited.dump(2) + "\n");
  CliOutcome o = run_closurelab(work, run_args(work));
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find(cell.string() + " does not match its checksum (edited or corrupt); recomputing it"),
            std::string::npos)
      << o.err;
  EXPECT_NE(read(cell)["cell_wall_seconds"], 1234.5);
  EXPECT_EQ(read(work / "out" / "summed.json")["rows"][0]["params"], before["rows"][0]["params"]);
  // Truncated (a full disk, a copy cut short).
  const std::string text = read_text(cell);
  write_text(cell, text.substr(0, text.size() / 2));
  o = run_closurelab(work, run_args(work));
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("truncated or unreadable: " + cell.string() + "; recomputing it"), std::string::npos) << o.err;
  EXPECT_NO_THROW(read(cell));
  // Nothing damaged now: a third run computes nothing and says nothing about checksums.
  o = run_closurelab(work, run_args(work));
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err.find("recomputing"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("does not match its checksum"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("carry no checksum"), std::string::npos) << o.err;
}

TEST(RunnerCellChecksum, MergeRefusesAnEditedCellAndNamesATruncatedOneAsSuch) {
  const auto work = fresh_work_folder("cell_checksum_merge");
  write_text(work / "summed.json", spec);
  run_shards(work);
  const fs::path cell = any_cell(work);
  const std::string good = read_text(cell);
  json edited = read(cell);
  edited["status"] = "ok";
  edited["label"] = "edited by hand";
  write_text(cell, edited.dump(2) + "\n");
  CliOutcome o = run_closurelab(work, "merge " + (work / "out").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("does not match its checksum (edited or corrupt): " + cell.string()), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("missing or unusable; nothing was written"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(work / "out" / "summed.json"));

  write_text(cell, good.substr(0, good.size() - 20));
  o = run_closurelab(work, "merge " + (work / "out").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("truncated or unreadable: " + cell.string()), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("missing cell"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(work / "out" / "summed.json"));

  // Re-running the shards (as merge says) recomputes the damaged cell; then merge writes the table.
  run_shards(work);
  o = run_closurelab(work, "merge " + (work / "out").string());
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_TRUE(fs::exists(work / "out" / "summed.json"));
}

TEST(RunnerCellChecksum, CellFilesWithoutAChecksumAreReusedAndMergedWithANote) {
  const auto work = fresh_work_folder("cell_checksum_legacy");
  write_text(work / "summed.json", spec);
  run_shards(work);
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(work / "out" / "cells")) {
    json row = read(e.path());
    row.erase(closurelab::cell_checksum_key);  // as an older closurelab wrote it
    write_text(e.path(), row.dump(2) + "\n");
    ++n;
  }
  ASSERT_EQ(n, 4u);
  CliOutcome o = run_closurelab(work, "merge " + (work / "out").string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("note: 4 cell file(s) carry no checksum"), std::string::npos) << o.err;
  const json merged = read(work / "out" / "summed.json");
  EXPECT_EQ(merged["rows"].size(), 4u);
  // A run on the folder reuses them (nothing started) and says so once.
  o = run_closurelab(work, run_args(work));
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err.find("started"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("note: 4 finished cell file(s) carry no checksum"), std::string::npos) << o.err;
  EXPECT_EQ(read(work / "out" / "summed.json")["rows"], merged["rows"]);
}
