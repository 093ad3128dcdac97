// `closurelab deconvolve` end to end on Matrix Market files: JSON output with the relative error, the
// solution file, and non-zero exits with a message for bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/io/matrix_market.hpp"
#include "experiments/runner/deconvolve_command.hpp"
#include "core/base/params.hpp"
#include "core/base/registry.hpp"

using namespace closurelab;

namespace {
struct Captured {
  int rc;
  std::string out, err;
};
Captured run(std::vector<std::string> args) {
  args.insert(args.begin(), {"closurelab", "deconvolve"});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  std::stringstream out, err;
  auto* old_out = std::cout.rdbuf(out.rdbuf());
  auto* old_err = std::cerr.rdbuf(err.rdbuf());
  const int rc = run_deconvolve_command(static_cast<int>(argv.size()), argv.data(), builtin_registry());
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  return {rc, out.str(), err.str()};
}
// One folder per test process: ctest runs the tests of this file in parallel processes, which would otherwise
// overwrite each other's inputs.
std::string dir() {
  const auto d = std::filesystem::temp_directory_path() / ("closurelab_deconvolve_cmd_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d.string();
}
}  // namespace

TEST(DeconvCommand, SolvesAWellPosedSystemAndReportsTheError) {
  // A diagonally dominant SPD matrix: every method recovers x to its tolerance.
  const int n = 12;
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n) * 4;
  for (int i = 0; i + 1 < n; ++i) a(i, i + 1) = a(i + 1, i) = -1;
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1, 2);
  const std::string d = dir();
  write_matrix_market(d + "/A.mtx", Eigen::SparseMatrix<double>(a.sparseView()));
  write_matrix_market(d + "/b.mtx", Eigen::MatrixXd(a * x));
  write_matrix_market(d + "/x.mtx", Eigen::MatrixXd(x));
  const Captured c = run({"--matrix", d + "/A.mtx", "--rhs", d + "/b.mtx", "--x-true", d + "/x.mtx", "--method", "cg",
                          "--param", "iterations=100", "--out", d + "/sol.mtx"});
  ASSERT_EQ(c.rc, 0) << c.err;
  const json j = json::parse(c.out);
  EXPECT_EQ(j["status"], "converged");
  EXPECT_LT(j["relative_error"].get<double>(), 1e-12);
  EXPECT_EQ(j["matrix"]["storage"], "sparse");
  EXPECT_EQ(j["method"]["iterations"], 100);
  EXPECT_LT((read_matrix_market_vector(d + "/sol.mtx") - x).norm(), 1e-12 * x.norm());
}

TEST(DeconvCommand, BadInputExitsNonZeroWithAMessage) {
  const std::string d = dir();
  write_matrix_market(d + "/A2.mtx", Eigen::MatrixXd(Eigen::MatrixXd::Identity(3, 3)));
  write_matrix_market(d + "/b4.mtx", Eigen::MatrixXd(Eigen::VectorXd::Ones(4)));
  std::ofstream(d + "/bad.mtx") << "%%MatrixMarket matrix array real general\n2 2\n1\n";
  struct Case {
    std::vector<std::string> args;
    std::string expect;
  };
  const std::vector<Case> cases = {
      {{"--matrix", d + "/A2.mtx", "--rhs", d + "/b4.mtx", "--method", "cgls"}, "4 entries"},
      {{"--matrix", d + "/missing.mtx", "--rhs", d + "/b4.mtx", "--method", "cgls"}, "cannot open"},
      {{"--matrix", d + "/bad.mtx", "--rhs", d + "/b4.mtx", "--method", "cgls"}, "file ends"},
      {{"--matrix", d + "/A2.mtx", "--rhs", d + "/b4.mtx", "--method", "magic"}, "unknown deconvolver"},
      {{"--matrix", d + "/A2.mtx", "--rhs", d + "/b4.mtx", "--method", "tikhonov", "--param", "alpha=0"}, "alpha"},
      {{"--matrix", d + "/A2.mtx", "--rhs", d + "/b4.mtx"}, "--method"},
      {{"--matrix", d + "/A2.mtx", "--rhs", d + "/b4.mtx", "--method", "cgls", "--noise-level", "x"}, "--noise-level"},
      {{"--bogus"}, "unknown option"}};
  for (const auto& c : cases) {
    const Captured r = run(c.args);
    EXPECT_NE(r.rc, 0) << c.expect;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
  }
}

TEST(DeconvCommand, IssueFourteenBigMatrixIsSolvedNotEmpty) {
  // A reported bad input: cgls on diag(1e300, 2e300) returned a 0 x 1 "solution" marked converged (and the
  // relative error then read past it: SIGSEGV). Now the operator is rescaled and x = (1e-300, 5e-301).
  const std::string d = dir();
  std::ofstream(d + "/big.mtx") << "%%MatrixMarket matrix array real general\n2 2\n1e300\n0\n0\n2e300\n";
  std::ofstream(d + "/b2.mtx") << "%%MatrixMarket matrix array real general\n2 1\n1\n1\n";
  for (const std::string method : {"cgls", "tikhonov", "landweber_relaxed", "cg", "tsvd"}) {
    SCOPED_TRACE(method);
    std::vector<std::string> args = {"--matrix", d + "/big.mtx", "--rhs", d + "/b2.mtx", "--x-true", d + "/b2.mtx",
                                     "--method", method};
    if (method == "landweber_relaxed") args.insert(args.end(), {"--param", "iterations=200"});
    if (method == "tsvd") args.insert(args.end(), {"--param", "k=2"});
    const Captured c = run(args);
    ASSERT_EQ(c.rc, 0) << c.err;
    const json j = json::parse(c.out);
    EXPECT_EQ(j["status"], "converged");
    ASSERT_EQ(j["x"].size(), 2u);
    EXPECT_NEAR(j["x"][0].get<double>(), 1e-300, 1e-312);
    EXPECT_NEAR(j["x"][1].get<double>(), 5e-301, 1e-312);
  }
}

TEST(DeconvCommand, NumericalIssueExitsOneAndStrictOptions) {
  const std::string d = dir();
  std::ofstream(d + "/tiny.mtx") << "%%MatrixMarket matrix array real general\n2 2\n1e-310\n0\n0\n2e-310\n";
  std::ofstream(d + "/b2.mtx") << "%%MatrixMarket matrix array real general\n2 1\n1\n1\n";
  const Captured c = run({"--matrix", d + "/tiny.mtx", "--rhs", d + "/b2.mtx", "--method", "tikhonov"});
  EXPECT_EQ(c.rc, 1);
  EXPECT_EQ(json::parse(c.out)["status"], "numerical_issue");
  EXPECT_NE(c.err.find("swamps"), std::string::npos) << c.err;
  EXPECT_EQ(run({"--matrix", d + "/tiny.mtx", "--rhs", d + "/b2.mtx", "--method", "cgls", "--noise-level", "0x10"}).rc, 2);
  EXPECT_EQ(run({"--matrix", d + "/tiny.mtx", "--rhs", d + "/b2.mtx", "--method", "cgls", "--param", "name=tsvd"}).rc, 2);
}
