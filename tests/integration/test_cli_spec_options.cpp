// `closurelab run --dry-run` (validate and print the resolved cells, write nothing), `--set KEY=VALUE` (holds in
// every cell), `run` without --out (into out/runs/<name>, never results/), and `closurelab export --csv`.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/base/params.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab::testing;
using closurelab::json;
namespace fs = std::filesystem;

namespace {

const char* const kTiny = R"({"name": "tiny", "kind": "direct_sph_validation",
  "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16},
           "solver": {"mode": "target_time", "target_time": 0.05}},
  "cells": [{"label": "a"}, {"label": "b", "solver": {"target_time": 0.1}}]})";

}  // namespace

TEST(CliSpecOptions, DryRunPrintsEveryResolvedCellAndWritesNothing) {
  const auto work = fresh_work_folder("cli_dry_run");
  write_text(work / "tiny.json", kTiny);
  const CliOutcome o = run_shell(work, "cd " + work.string() + " && " + std::string(CLOSURELAB_BINARY_DIR) +
                                           "/experiments/closurelab run tiny.json --dry-run --set scene.n_x=13");
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("2 cell(s), all valid"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("\"n_x\": 13"), std::string::npos) << o.out;       // --set, in the resolved cells
  EXPECT_NE(o.out.find("\"sound_speed_factor\""), std::string::npos);     // a default filled in
  // Cell b's solver object kept the base's mode (deep merge).
  EXPECT_EQ(o.out.find("\"mode\": \"steady\""), std::string::npos) << o.out;
  EXPECT_FALSE(fs::exists(work / "out"));
  EXPECT_FALSE(fs::exists(work / "results"));
  // An invalid cell: exit 2, the JSON path named, nothing written.
  const CliOutcome bad = run_shell(work, "cd " + work.string() + " && " + std::string(CLOSURELAB_BINARY_DIR) +
                                             "/experiments/closurelab run tiny.json --dry-run --set scene.n_y=-3");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("/scene/n_y"), std::string::npos) << bad.err;
}

TEST(CliSpecOptions, RunWithoutOutWritesIntoOutRunsAndExportsCsv) {
  const auto work = fresh_work_folder("cli_default_out");
  write_text(work / "tiny.json", kTiny);
  const std::string exe = std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab";
  const CliOutcome o = run_shell(work, "cd " + work.string() + " && " + exe + " run tiny.json");
  ASSERT_EQ(o.code, 0) << o.err;
  const fs::path table = work / "out" / "runs" / "tiny" / "tiny.json";
  ASSERT_TRUE(fs::exists(table));
  EXPECT_FALSE(fs::exists(work / "results"));
  const json t = closurelab::read_json_file(table.string());
  ASSERT_EQ(t.at("rows").size(), 2u);
  EXPECT_EQ(t["rows"][1].at("params").at("solver").at("mode"), "target_time");
  EXPECT_EQ(t["rows"][1].at("params").at("solver").at("target_time"), 0.1);
  // CSV: a header and one record per row, with the leading columns and a dotted error column.
  const CliOutcome csv = run_shell(work, exe + " export " + table.string() + " --csv");
  ASSERT_EQ(csv.code, 0) << csv.err;
  std::size_t lines = 0;
  for (char c : csv.out) lines += c == '\n';
  EXPECT_EQ(lines, 3u) << csv.out;
  EXPECT_EQ(csv.out.rfind("id,label,status,", 0), 0u) << csv.out.substr(0, 200);
  EXPECT_NE(csv.out.find("params.scene.n_y"), std::string::npos);
  EXPECT_NE(csv.out.find("cost."), std::string::npos);
}
