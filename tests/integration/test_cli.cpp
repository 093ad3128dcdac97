// The closurelab command line end to end: a tiny experiment runs, writes a complete table with
// provenance and resumes; bad input gives a clear message naming the JSON path, exit code 2 and no table.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/base/params.hpp"

namespace fs = std::filesystem;
using closurelab::json;

namespace {

struct Outcome {
  int code;
  std::string err;
};

// One folder per test process: ctest runs the cases in parallel processes.
const fs::path work = fs::temp_directory_path() / ("closurelab_cli_test_" + std::to_string(getpid()));

// Removes this process's folder when the tests end.
class RemoveWorkFolder : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(work); }
};
const auto* const remove_work_folder = ::testing::AddGlobalTestEnvironment(new RemoveWorkFolder);

Outcome run_cli(const std::string& args) {
  const fs::path err = work / "stderr.txt";
  const std::string cmd = std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab " + args + " 2>" + err.string() + " >" +
                          (work / "stdout.txt").string();
  const int status = std::system(cmd.c_str());
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

fs::path write_spec(const std::string& name, const std::string& text) {
  fs::create_directories(work);
  const fs::path p = work / name;
  std::ofstream(p) << text;
  return p;
}

std::string tiny_spec(const std::string& scene_extra) {
  return R"({"name": "tiny", "kind": "direct_sph_validation",
    "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16)" + scene_extra + R"(},
             "solver": {"mode": "target_time", "target_time": 0.05}}})";
}

}  // namespace

TEST(Cli, TinyExperimentRunsWritesProvenanceAndResumes) {
  fs::remove_all(work / "out");
  const fs::path spec = write_spec("tiny.json", tiny_spec(""));
  const Outcome first = run_cli("run " + spec.string() + " --out " + (work / "out").string());
  ASSERT_EQ(first.code, 0) << first.err;
  const json table = closurelab::read_json_file((work / "out" / "tiny.json").string());
  EXPECT_TRUE(table.at("complete").get<bool>());
  ASSERT_EQ(table.at("rows").size(), 1u);
  const json& row = table["rows"][0];
  EXPECT_EQ(row.at("status"), "ok");
  EXPECT_EQ(row.at("params").at("scene").at("n_x"), 12);  // defaults are echoed
  EXPECT_GT(row.at("cost").at("steps").get<int>(), 0);
  for (const char* key : {"git_commit", "dirty", "compiler", "build_type", "date_utc", "host", "threads"})
    EXPECT_TRUE(row.at("provenance").contains(key)) << key;  // each row: the run that computed it
  EXPECT_EQ(table.at("provenance").at("commits"), closurelab::json::array({row["provenance"]["git_commit"]}));
  const Outcome again = run_cli("run " + spec.string() + " --out " + (work / "out").string());
  EXPECT_EQ(again.code, 0);
  EXPECT_NE(again.err.find("already done"), std::string::npos) << again.err;
}

struct BadCase {
  const char* what;
  std::string spec;
  const char* expected;  // a fragment of the message (the JSON path)
};

class CliBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(CliBadInput, ClearMessageNonZeroExitNoTable) {
  const auto& c = GetParam();
  fs::remove_all(work / "bad");
  const fs::path spec = write_spec("bad.json", c.spec);
  const Outcome o = run_cli("run " + spec.string() + " --out " + (work / "bad").string());
  EXPECT_EQ(o.code, 2) << c.what << ": " << o.err;
  EXPECT_NE(o.err.find(c.expected), std::string::npos) << c.what << ": " << o.err;
  EXPECT_FALSE(fs::exists(work / "bad" / "tiny.json")) << c.what;
}

INSTANTIATE_TEST_SUITE_P(
    Specs, CliBadInput,
    ::testing::Values(
        BadCase{"unknown scene", R"({"name":"tiny","kind":"direct_sph_validation","base":{"scene":{"name":"couette"}}})",
                "/base/scene/name"},
        BadCase{"unknown kernel",
                R"({"name":"tiny","kind":"direct_sph_validation","base":{"scene":{"name":"poiseuille-uniform"},"kernel":{"name":"box"}}})",
                "unknown kernel 'box'"},
        BadCase{"unknown key", tiny_spec(R"(, "n_z": 3)"), "/base/scene/n_z"},
        BadCase{"wrong type", tiny_spec(R"(, "n_x": "twelve")"), "/base/scene/n_x"},
        BadCase{"negative spacing", tiny_spec(R"(, "n_y": -48)"), "/base/scene/n_y"},
        BadCase{"eta too large", tiny_spec(R"(, "eta_over_ly": 0.2)"), "/base/scene/eta_over_l"},
        BadCase{"non-finite", R"({"name":"tiny","kind":"direct_sph_validation","base":{"scene":{"name":"poiseuille-uniform","g":1e999}}})",
                "malformed JSON"},
        BadCase{"malformed JSON", R"({"name": "tiny", "kind": )", "malformed JSON"},
        BadCase{"unknown experiment kind", R"({"name":"tiny","kind":"nope"})", "/kind"},
        BadCase{"bad axis", R"({"name":"tiny","kind":"direct_sph_validation","base":{},"axes":{"scene.n_y":7}})",
                "/axes/scene.n_y"}));

TEST(Cli, UnknownCommandAndFamily) {
  fs::create_directories(work);
  EXPECT_EQ(run_cli("frobnicate").code, 2);
  EXPECT_EQ(run_cli("list nonsense").code, 2);
  EXPECT_EQ(run_cli("list kernel").code, 0);
  EXPECT_EQ(run_cli("run /nonexistent/spec.json").code, 2);
}
