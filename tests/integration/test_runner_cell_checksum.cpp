// The checksum of a cell file (DIR/cells/<id>.json, results_table.hpp): a run writes it; a resumed run recomputes a
// cell whose file was edited by hand or is truncated, saying so and naming the file; `merge` refuses such a cell
// ("does not match its checksum" / "truncated or unreadable: FILE", never "missing") and writes no table; so is a
// cell file without a checksum (a hand edit that deleted the key cannot be told from an older closurelab's file),
// and merge says how to seal a folder of trusted old cells: `closurelab seal DIR` adds the key, the row unchanged.
// Runs in about 2 s (cells of a 16-row channel to t = 0.02..0.04, a few ms each).
#include <gtest/gtest.h>

#include <map>

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
  EXPECT_EQ(o.err.find("no checksum"), std::string::npos) << o.err;
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

// As an older closurelab wrote them: every cell file without the key (`reformat`: indented by 4, not 2).
std::size_t strip_checksums(const fs::path& work, bool reformat = false) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(work / "out" / "cells")) {
    json row = read(e.path());
    row.erase(closurelab::cell_checksum_key);
    write_text(e.path(), row.dump(reformat ? 4 : 2) + "\n");
    ++n;
  }
  return n;
}

TEST(RunnerCellChecksum, ACellFileWithoutAChecksumIsRecomputedByARunAndRefusedByMergeWhichSaysHowToSeal) {
  const auto work = fresh_work_folder("cell_checksum_unsealed");
  write_text(work / "summed.json", spec);
  run_shards(work);
  const fs::path cell = any_cell(work);
  // A hand edit that also deletes the key: the file cannot be told from an old one, so neither is trusted.
  json edited = read(cell);
  edited.erase(closurelab::cell_checksum_key);
  edited["status"] = "ok";
  edited["label"] = "edited by hand";
  write_text(cell, edited.dump(2) + "\n");
  const fs::path out = work / "out";
  CliOutcome o = run_closurelab(work, "merge " + out.string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("carries no checksum (cell_fnv1a64: written before cells were sealed, or edited with the key "
                       "deleted): " + cell.string()),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("seal the folder first: closurelab seal " + out.string()), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("1 of 4 cell(s) missing or unusable; nothing was written"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(out / "summed.json"));

  // A run recomputes it, naming the file, and seals what it writes; then merge writes the table.
  o = run_closurelab(work, run_args(work));
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find(cell.string() + " carries no checksum"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("; recomputing it"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("note: 1 cell file(s) without a checksum are recomputed"), std::string::npos) << o.err;
  EXPECT_TRUE(read(cell).contains(closurelab::cell_checksum_key));
  EXPECT_NE(read(cell)["label"], "edited by hand");
  fs::remove(out / "summed.json");
  o = run_closurelab(work, "merge " + out.string());
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err.find("no checksum"), std::string::npos) << o.err;
}

TEST(RunnerCellChecksum, SealAddsTheChecksumToOldCellsTheirRowsUnchangedThenTheyAreReusedAndMerged) {
  const auto work = fresh_work_folder("cell_checksum_seal");
  write_text(work / "summed.json", spec);
  run_shards(work);
  const fs::path out = work / "out";
  std::map<fs::path, std::string> sealed_by_run;
  for (const auto& e : fs::directory_iterator(out / "cells")) sealed_by_run[e.path()] = read_text(e.path());
  ASSERT_EQ(strip_checksums(work), 4u);
  std::map<fs::path, std::string> old;
  for (const auto& [f, text] : sealed_by_run) old[f] = read_text(f);

  // --dry-run writes nothing; seal writes each file as the run had (the same bytes: only the key's line added).
  CliOutcome o = run_closurelab(work, "seal " + out.string() + " --dry-run");
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("4 cell file(s) to seal (0 with other formatting), 0 already sealed, 0 not sealed"),
            std::string::npos)
      << o.err;
  for (const auto& [f, text] : old) EXPECT_EQ(read_text(f), text);
  o = run_closurelab(work, "seal " + out.string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("4 cell file(s) sealed (0 with other formatting), 0 already sealed, 0 not sealed"),
            std::string::npos)
      << o.err;
  for (const auto& [f, text] : sealed_by_run) EXPECT_EQ(read_text(f), text) << f;
  // Sealing again changes nothing.
  o = run_closurelab(work, "seal " + out.string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("0 cell file(s) sealed (0 with other formatting), 4 already sealed"), std::string::npos) << o.err;

  // Merged and reused without a word about checksums; a run computes nothing.
  o = run_closurelab(work, "merge " + out.string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err.find("no checksum"), std::string::npos) << o.err;
  const std::string table = read_text(out / "summed.json");
  o = run_closurelab(work, run_args(work));
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err.find("started"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("no checksum"), std::string::npos) << o.err;
  EXPECT_EQ(read_text(out / "summed.json"), table);
}

TEST(RunnerCellChecksum, SealNamesAFileItReformatsAndRefusesAnEditedOrUnreadableOne) {
  const auto work = fresh_work_folder("cell_checksum_seal_refuses");
  write_text(work / "summed.json", spec);
  run_shards(work);
  const fs::path out = work / "out";
  std::map<fs::path, json> rows;
  for (const auto& e : fs::directory_iterator(out / "cells")) rows[e.path()] = read(e.path());
  auto it = rows.begin();
  const fs::path edited = (it++)->first, reformatted = (it++)->first, truncated = (it++)->first;
  json e = rows[edited];
  e["status"] = "numerical_issue";  // the key kept: the checksum does not match
  write_text(edited, e.dump(2) + "\n");
  json r = rows[reformatted];
  r.erase(closurelab::cell_checksum_key);
  write_text(reformatted, r.dump(4) + "\n");
  write_text(truncated, "{\"id\": ");
  const std::string edited_text = read_text(edited);

  CliOutcome o = run_closurelab(work, "seal " + out.string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("error: " + edited.string() + " does not match its checksum (edited or corrupt); not sealed"),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("error: " + truncated.string() + " truncated or unreadable"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("note: " + reformatted.string() + ": its formatting changed"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("1 cell file(s) sealed (1 with other formatting), 1 already sealed, 2 not sealed"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(read_text(edited), edited_text);
  EXPECT_EQ(read_text(truncated), "{\"id\": ");
  json back = read(reformatted);
  EXPECT_EQ(back, rows[reformatted]);  // the row and the checksum the run had written

  // No cells folder: exit 2, nothing created.
  o = run_closurelab(work, "seal " + (work / "nowhere").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("no folder"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(work / "nowhere"));
}
