// Every committed experiment spec (experiments/**/*.json) validates: it parses under the guarded reader
// (depth, duplicate keys), expands, names a known kind, and every cell resolves, exactly as `closurelab run`
// checks before it runs anything. A spec broken by a schema change fails here,
// not hours into scripts/reproduce.sh.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/base/errors.hpp"
#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/runner.hpp"

using namespace closurelab;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> committed_specs() {
  std::vector<std::string> files;
  const fs::path root = fs::path(CLOSURELAB_SOURCE_DIR) / "experiments";
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(fs::relative(e.path(), root).string());
  std::sort(files.begin(), files.end());
  return files;
}

class CommittedSpec : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST(CommittedSpecs, ThereAreSpecsToCheck) { EXPECT_GE(committed_specs().size(), 10u); }

TEST_P(CommittedSpec, Validates) {
  // The committed specs run from the repository root (README): a reference.file path is relative to it.
  struct RestoreCwd {
    fs::path was = fs::current_path();
    ~RestoreCwd() { fs::current_path(was); }
  } restore;
  fs::current_path(CLOSURELAB_SOURCE_DIR);
  const std::string file = (fs::path(CLOSURELAB_SOURCE_DIR) / "experiments" / GetParam()).string();
  try {
    const json spec = read_json_file(file);
    const std::vector<MatrixCell> cells = expand_matrix(spec);
    ASSERT_FALSE(cells.empty());
    const ExperimentKind& kind = builtin_registry().experiments.get(spec.at("kind").get<std::string>(), "/kind");
    for (const auto& c : cells) {
      SCOPED_TRACE(c.label);
      const json r = kind.resolve(c.config, c.path, builtin_registry());
      EXPECT_TRUE(r.is_object());
    }
  } catch (const ConfigError& e) {
    FAIL() << GetParam() << ": " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Experiments, CommittedSpec, ::testing::ValuesIn(committed_specs()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           for (auto& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });
