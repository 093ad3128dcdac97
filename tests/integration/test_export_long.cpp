// `closurelab export`: CSV without being asked (--csv still accepted, the same bytes), and --long, the rows' coarse
// fields and profiles one record per node, each value at its node: (x[i], y[j]) holds list element j nx + i (the
// layout of docs/row_schema.md), a profile's records have empty i and x, a failed row has none; on a made-up table
// and on the committed cylinder table through the command line.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>

#include "core/base/params.hpp"
#include "experiments/runner/export_command.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab;
using namespace closurelab::testing;

namespace {

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {  // no quoted commas in these tables
  std::vector<std::vector<std::string>> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream ls(line);
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    out.push_back(cells);
  }
  return out;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
}

}  // namespace

TEST(ExportLong, EachNodeValueIsAtItsNodeAndAProfileHasNoX) {
  const json table = {
      {"rows",
       {{{"id", "a"},
         {"label", "two-d"},
         {"status", "ok"},
         {"fields",
          {{"x", {0.25, 0.75}},
           {"y", {0.1, 0.2, 0.3}},
           {"reduced", {{"vx", {0, 1, 2, 3, 4, 5}}, {"vy", {10, 11, 12, 13, 14, 15}}}},
           {"outside_solid", {true, false, true, true, true, true}}}}},
        {{"id", "b"}, {"label", "column"}, {"status", "ok"}, {"profile", {{"y", {0.5, 1.5}}, {"reduced", {7, 8}}}}},
        {{"id", "c"}, {"label", "failed"}, {"status", "error"}}}}};
  const auto csv = parse_csv(table_to_long_csv(table));
  ASSERT_EQ(csv.size(), 1u + 6u + 2u);  // the header, 2 x 3 nodes, 2 profile nodes; the failed row none
  const auto& h = csv[0];
  EXPECT_EQ((std::vector<std::string>(h.begin(), h.begin() + 6)),
            (std::vector<std::string>{"id", "label", "i", "j", "x", "y"}));
  const std::size_t vx = column(h, "reduced_vx"), vy = column(h, "reduced_vy"), solid = column(h, "outside_solid"),
                    reduced = column(h, "reduced");
  ASSERT_LT(std::max({vx, vy, solid, reduced}), h.size());
  for (std::size_t r = 1; r <= 6; ++r) {
    const auto& c = csv[r];
    const int i = std::stoi(c[2]), j = std::stoi(c[3]);
    EXPECT_EQ(std::stod(c[4]), i == 0 ? 0.25 : 0.75);
    EXPECT_EQ(std::stod(c[5]), (std::vector<double>{0.1, 0.2, 0.3}[j]));
    EXPECT_EQ(std::stod(c[vx]), j * 2 + i);  // element j nx + i
    EXPECT_EQ(std::stod(c[vy]), 10 + j * 2 + i);
    EXPECT_EQ(c[solid], (i == 1 && j == 0) ? "false" : "true");
    EXPECT_EQ(c[reduced], "");  // a 2D row has no profile column
  }
  for (std::size_t r = 7; r <= 8; ++r) {
    const auto& c = csv[r];
    EXPECT_EQ(c[0], "b");
    EXPECT_EQ(c[2], "");
    EXPECT_EQ(c[4], "");
    EXPECT_EQ(std::stod(c[5]), r == 7 ? 0.5 : 1.5);
    EXPECT_EQ(std::stod(c[reduced]), r == 7 ? 7.0 : 8.0);
    EXPECT_EQ(c[vx], "");
  }
}

TEST(ExportLong, TheCommittedCylinderTableExportsWithoutCsvAndItsFieldsLong) {
  const auto work = fresh_work_folder("export_long");
  const std::string table_file = std::string(CLOSURELAB_SOURCE_DIR) + "/results/cylinders/reduced/reduced.json";
  const CliOutcome plain = run_closurelab(work, "export " + table_file);
  const CliOutcome with_csv = run_closurelab(work, "export " + table_file + " --csv");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.out, with_csv.out);
  EXPECT_EQ(plain.out.rfind("id,label,status,", 0), 0u);

  const CliOutcome long_csv = run_closurelab(work, "export " + table_file + " --long");
  ASSERT_EQ(long_csv.code, 0) << long_csv.err;
  const json table = read_json_file(table_file);
  std::size_t nodes = 0;
  for (const json& row : table.at("rows"))
    if (row.contains("fields")) nodes += row["fields"]["x"].size() * row["fields"]["y"].size();
  const auto csv = parse_csv(long_csv.out);
  ASSERT_EQ(csv.size(), 1u + nodes);
  ASSERT_GT(nodes, 0u);
  // Every record's reduced and direct values against the row's lists at j nx + i.
  const auto& h = csv[0];
  const std::size_t vx = column(h, "reduced_vx"), dvy = column(h, "direct_average_vy");
  ASSERT_LT(std::max(vx, dvy), h.size());
  std::map<std::string, const json*> by_id;
  for (const json& row : table.at("rows")) by_id[row.at("id").get<std::string>()] = &row;
  for (std::size_t r = 1; r < csv.size(); ++r) {
    const json& f = by_id.at(csv[r][0])->at("fields");
    const std::size_t i = std::stoul(csv[r][2]), j = std::stoul(csv[r][3]), node = j * f["x"].size() + i;
    ASSERT_EQ(std::stod(csv[r][4]), f["x"][i].get<double>()) << r;
    ASSERT_EQ(std::stod(csv[r][5]), f["y"][j].get<double>()) << r;
    ASSERT_EQ(std::stod(csv[r][vx]), f["reduced"]["vx"][node].get<double>()) << r;
    ASSERT_EQ(std::stod(csv[r][dvy]), f["direct_average"]["vy"][node].get<double>()) << r;
  }
}
