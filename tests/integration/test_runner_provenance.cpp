// Provenance that cannot lie: each row keeps the provenance of the run that computed it; the table's header is
// derived from its rows (the commits they came from, how many from a dirty build); a re-run that computes
// nothing leaves the table and its summary byte-identical, also when its rows came from another commit.
#include <gtest/gtest.h>

#include <set>

#include "core/base/params.hpp"
#include "experiments/runner/results_table.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using closurelab::json;
using namespace closurelab::testing;

namespace {

const char* two_cell_spec = R"({"name": "prov", "kind": "direct_sph_validation",
  "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16},
           "solver": {"mode": "target_time", "target_time": 0.02}},
  "axes": {"solver.target_time": [0.02, 0.04]}})";

json read(const fs::path& p) { return closurelab::read_json_file(p.string()); }

}  // namespace

TEST(RunnerProvenance, RowsKeepTheirRunAndACachedRerunChangesNothing) {
  const auto work = fresh_work_folder("provenance");
  write_text(work / "prov.json", two_cell_spec);
  const std::string run = "run " + (work / "prov.json").string() + " --out " + (work / "out").string();
  const fs::path table_file = work / "out" / "prov.json";

  const CliOutcome first = run_closurelab(work, run);
  ASSERT_EQ(first.code, 0) << first.err;
  const json t1 = read(table_file);
  ASSERT_EQ(t1.at("rows").size(), 2u);
  std::string commit;
  for (const json& row : t1["rows"]) {
    const json& p = row.at("provenance");
    for (const char* key : {"git_commit", "dirty", "compiler", "cxx_flags", "build_type", "date_utc", "host", "threads",
                            "sph_pair_kernel", "command"})
      EXPECT_TRUE(p.contains(key)) << key;
    EXPECT_EQ(p["git_commit"].get<std::string>().find("-dirty"), std::string::npos);  // the flag says it
    // The code-generation options of every target are recorded with the build type's flags.
    EXPECT_NE(p["cxx_flags"].get<std::string>().find("-fno-trapping-math"), std::string::npos) << p["cxx_flags"];
    EXPECT_TRUE(p["sph_pair_kernel"] == "baseline" || p["sph_pair_kernel"] == "avx2" ||
                p["sph_pair_kernel"] == "avx512")
        << p["sph_pair_kernel"];
    commit = p["git_commit"].get<std::string>();
  }
  // The header comes from the rows only: no date of its own, the rows' commits.
  const json& tp = t1.at("provenance");
  EXPECT_EQ(tp.at("derived_from"), "rows");
  EXPECT_EQ(tp.at("commits"), json::array({commit}));
  EXPECT_FALSE(tp.contains("date_utc"));
  const std::string bytes1 = read_text(table_file);

  // Everything cached: nothing computed, the table byte-identical.
  const CliOutcome second = run_closurelab(work, run + " --jobs 2");
  ASSERT_EQ(second.code, 0) << second.err;
  EXPECT_EQ(second.err.find("started"), std::string::npos) << second.err;
  EXPECT_EQ(read_text(table_file), bytes1);

  // As if the first cell had been computed at another commit by a dirty build: its row keeps that provenance
  // and the header lists both commits and one dirty row.
  const fs::path cell = work / "out" / "cells" / (t1["rows"][0]["id"].get<std::string>() + ".json");
  json row0 = read(cell);
  row0["provenance"]["git_commit"] = "0123456789ab";
  row0["provenance"]["dirty"] = true;
  row0[closurelab::cell_checksum_key] = closurelab::cell_checksum(row0);  // as that build would have written it
  write_text(cell, row0.dump(2) + "\n");
  const CliOutcome third = run_closurelab(work, run);
  ASSERT_EQ(third.code, 0) << third.err;
  EXPECT_EQ(third.err.find("started"), std::string::npos) << third.err;
  const json t3 = read(table_file);
  EXPECT_EQ(t3["rows"][0]["provenance"]["git_commit"], "0123456789ab");
  EXPECT_EQ(t3["rows"][1]["provenance"], t1["rows"][1]["provenance"]);
  EXPECT_EQ(t3["provenance"]["commits"], json(std::set<std::string>{"0123456789ab", commit}));
  // This build itself may be dirty (a working tree with changes): then the other row counts too.
  const int dirty_rows = 1 + (t1["rows"][1]["provenance"]["dirty"].get<bool>() ? 1 : 0);
  EXPECT_EQ(t3["provenance"]["dirty_rows"], dirty_rows);
  const std::string bytes3 = read_text(table_file);

  // The summary names both commits and marks the dirty row; regenerated after another cached run, it is
  // byte-identical, and so is the table.
  // The Markdown alone (--no-figures): what is checked is its provenance, and the summaries' figures need matplotlib,
  // which the python3 on PATH need not have (the summaries' own tests run Debian's).
  const std::string summarize = "python3 " + std::string(CLOSURELAB_SOURCE_DIR) +
                                "/experiments/summaries/summarize.py --no-figures " + table_file.string() + " " +
                                (work / "summary").string();
  const CliOutcome s1 = run_shell(work, summarize);
  ASSERT_EQ(s1.code, 0) << s1.err;
  const std::string md1 = read_text(work / "summary" / "summary.md");
  const std::set<std::string> both{"0123456789ab", commit};
  const std::string commits = *both.begin() + ", " + *both.rbegin();
  EXPECT_NE(md1.find(commits + " (" + std::to_string(dirty_rows) + " row(s) from a dirty build)"), std::string::npos)
      << md1;
  EXPECT_NE(md1.find("[dirty build]"), std::string::npos) << md1;
  ASSERT_EQ(run_closurelab(work, run).code, 0);
  EXPECT_EQ(read_text(table_file), bytes3);
  ASSERT_EQ(run_shell(work, summarize).code, 0);
  EXPECT_EQ(read_text(work / "summary" / "summary.md"), md1);
}

TEST(RunnerProvenance, ATableFromBeforeRowsHadProvenanceIsLeftAsItIsWhenNothingIsComputed) {
  const auto work = fresh_work_folder("provenance_legacy");
  write_text(work / "prov.json", two_cell_spec);
  const std::string run = "run " + (work / "prov.json").string() + " --out " + (work / "out").string();
  ASSERT_EQ(run_closurelab(work, run).code, 0);
  // Rewrite the table and cells in the older format: one run's provenance in the header, none in the rows.
  const fs::path table_file = work / "out" / "prov.json";
  json t = read(table_file);
  t["provenance"] = {{"git_commit", "feedfacefeed"}, {"date_utc", "2026-01-01T00:00:00Z"}};
  for (json& row : t["rows"]) {
    row.erase("provenance");
    write_text(work / "out" / "cells" / (row["id"].get<std::string>() + ".json"), row.dump(2) + "\n");
  }
  write_text(table_file, t.dump(2) + "\n");
  const std::string before = read_text(table_file);
  // Cell files of that age carry no checksum: sealed (as the committed results were), they are reused.
  const CliOutcome sealed = run_closurelab(work, "seal " + (work / "out").string());
  ASSERT_EQ(sealed.code, 0) << sealed.err;
  const CliOutcome again = run_closurelab(work, run);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.err.find("started"), std::string::npos) << again.err;
  EXPECT_EQ(read_text(table_file), before);
}
