// Input guards: integer parameters checked in the type they are read into, JSON nesting
// depth, duplicate keys and non-regular files (items 6, 8, 12), the spec's top level (items 7, 10, 12), the
// Matrix Market reader's strictness and size checks (items 8, 12), and the allocation guard (item 8).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/support/config_error.hpp"
#include "core/base/errors.hpp"
#include "core/base/json_reader.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/params.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/io/matrix_market.hpp"
#include "experiments/runner/runner.hpp"

using namespace closurelab;
namespace fs = std::filesystem;

namespace {

using test_support::config_error;

fs::path scratch(const std::string& name, const std::string& text) {
  const fs::path d = fs::temp_directory_path() / ("closurelab_input_guards_" + std::to_string(getpid()));
  fs::create_directories(d);
  std::ofstream(d / name) << text;
  return d / name;
}

TEST(IntegerParams, ValuesBeyondTheReadTypeAreRefusedWithThePath) {
  const ParamSchema s{integer_param("steady_window", 1000, "window", 1, {})};
  for (const json& v : {json(4294967296LL), json(2147483648LL), json(18446744073709551615ULL)}) {
    const std::string e = config_error([&] { resolve_params(json{{"steady_window", v}}, s, "/solver"); });
    EXPECT_NE(e.find("/solver/steady_window"), std::string::npos) << e;
    EXPECT_NE(e.find("32-bit"), std::string::npos) << e;
  }
  EXPECT_EQ(resolve_params(json{{"steady_window", 2147483647}}, s, "/s")["steady_window"].get<int>(), 2147483647);
}

TEST(IntegerParams, WideKindsAcceptTheirRangeOnly) {
  const ParamSchema s64{integer_param("max_steps", 1, "steps", 1, {}, IntegerKind::int64)};
  EXPECT_EQ(resolve_params(json{{"max_steps", 4294967296LL}}, s64, "")["max_steps"].get<std::int64_t>(), 4294967296LL);
  EXPECT_NE(config_error([&] { resolve_params(json{{"max_steps", 9223372036854775808ULL}}, s64, ""); }), "");
  const ParamSchema su{integer_param("seed", 1, "seed", 0, {}, IntegerKind::uint64)};
  EXPECT_EQ(resolve_params(json{{"seed", 18446744073709551615ULL}}, su, "")["seed"].get<std::uint64_t>(),
            18446744073709551615ULL);
  EXPECT_NE(config_error([&] { resolve_params(json{{"seed", -1}}, su, ""); }), "");
}

TEST(JsonReader, DeepNestingIsRefusedBeforeAnyCopy) {
  // 100,000 levels (a reported 200 kB spec) overflowed the stack in the recursive copies of the expansion.
  const std::string deep = "{\"name\": \"x\", \"kind\": \"k\", \"base\": " + std::string(100000, '[') +
                           std::string(100000, ']') + "}";
  const std::string e = config_error([&] { parse_json_guarded(deep, "deep.json"); });
  EXPECT_NE(e.find("nested more than 64"), std::string::npos) << e;
  EXPECT_NE(e.find("/base"), std::string::npos) << e;
  // 64 levels are fine.
  EXPECT_NO_THROW(parse_json_guarded(std::string(63, '[') + std::string(63, ']'), "ok"));
}

TEST(JsonReader, DuplicateKeysNameTheirPath) {
  const std::string e =
      config_error([] { parse_json_guarded(R"({"base": {"scene": {"n_y": 16, "n_y": 32}}})", "dup.json"); });
  EXPECT_NE(e.find("/base/scene/n_y"), std::string::npos) << e;
  EXPECT_NE(e.find("duplicate key"), std::string::npos) << e;
  EXPECT_NO_THROW(parse_json_guarded(R"([{"a": 1}, {"a": 2}])", "ok"));  // one key per object
}

TEST(JsonReader, DevicesAndMissingFilesAreRefused) {
  EXPECT_NE(config_error([] { read_json_file("/dev/zero"); }).find("not a regular file"), std::string::npos);
  EXPECT_NE(config_error([] { read_json_file("/nonexistent/spec.json"); }), "");
}

TEST(SpecTopLevel, TypesNamesAndCellsAreCheckedBeforeExpansion) {
  const json ok = {{"name", "t"}, {"kind", "k"}, {"base", json::object()}};
  auto error_with = [&](const std::string& key, const json& value) {
    json s = ok;
    s[key] = value;
    return config_error([&] { expand_matrix(s); });
  };
  EXPECT_NE(error_with("description", 42).find("/description"), std::string::npos);
  for (const char* bad : {"../x", "/tmp/x", "", ".hidden", "a/b"})
    EXPECT_NE(error_with("name", bad).find("/name"), std::string::npos) << bad;
  EXPECT_NE(error_with("cells", json::array()).find("/cells"), std::string::npos);
  const std::string dup = error_with("cells", json::array({json{{"x", 1}}, json{{"x", 1}}}));
  EXPECT_NE(dup.find("/cells/1"), std::string::npos) << dup;
  EXPECT_NE(dup.find("/cells/0"), std::string::npos) << dup;
  EXPECT_EQ(expand_matrix(ok).size(), 1u);
}

TEST(MatrixMarketGuards, DeclaredSizesMustFitTheFile) {
  // A reported 3-line file declaring 30000 x 30000 allocated 7 GB before failing.
  const fs::path big = scratch("big.mtx", "%%MatrixMarket matrix array real general\n30000 30000\n1\n");
  EXPECT_NE(config_error([&] { read_matrix_market(big.string()); }).find("declares"), std::string::npos);
  const fs::path nnz = scratch("nnz.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 5000000000000000000\n1 1 1\n");
  EXPECT_NE(config_error([&] { read_matrix_market(nnz.string()); }).find("declares"), std::string::npos);
  EXPECT_NE(config_error([] { read_matrix_market("/dev/zero"); }).find("not a regular file"), std::string::npos);
}

TEST(MatrixMarketGuards, ExtraTokensAndFractionalIntegersAreRefused) {
  const fs::path extra = scratch("extra.mtx", "%%MatrixMarket matrix array real general\n2 1\n1 7\n2\n");
  EXPECT_NE(config_error([&] { read_matrix_market(extra.string()); }).find("extra token"), std::string::npos);
  const fs::path frac = scratch("frac.mtx", "%%MatrixMarket matrix array integer general\n2 1\n1\n2.5\n");
  EXPECT_NE(config_error([&] { read_matrix_market(frac.string()); }).find("non-integer"), std::string::npos);
  const fs::path size = scratch("size.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 5e18\n1 1 1\n");
  EXPECT_NE(config_error([&] { read_matrix_market(size.string()); }).find("5e18"), std::string::npos);
}

TEST(MemoryGuard, ADenseCopyBeyondTheLimitIsRefusedWithTheEstimate) {
  Eigen::SparseMatrix<double> s(1000000, 1000000);
  const std::vector<Eigen::Triplet<double>> t = {{0, 0, 1.0}};
  s.setFromTriplets(t.begin(), t.end());
  const ForwardOperator a = ForwardOperator::from_sparse(s);
  const std::string e = config_error([&] { a.to_dense(); });
  EXPECT_NE(e.find("8.0 TB"), std::string::npos) << e;
  EXPECT_NE(e.find("memory limit"), std::string::npos) << e;
  EXPECT_NE(config_error([] { check_particle_memory(100000, 4096, "/n_x"); }).find("/n_x"), std::string::npos);
}

}  // namespace
