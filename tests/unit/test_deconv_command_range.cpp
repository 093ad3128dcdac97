// Finite error norms at `closurelab deconvolve`: the relative error of a solution of 1e200 is a finite number
// (before: ||x - x_true|| / ||x_true|| = inf / inf, printed as null).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "core/io/matrix_market.hpp"
#include "experiments/runner/deconvolve_command.hpp"

using namespace closurelab;

TEST(DeconvCommandRange, RelativeErrorOfHugeSolutionsIsFinite) {
  const auto d = std::filesystem::temp_directory_path() / ("closurelab_deconvolve_range_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::Vector2d b(1e200, 2e200);
  write_matrix_market((d / "A.mtx").string(), a);
  write_matrix_market((d / "b.mtx").string(), Eigen::MatrixXd(b));
  write_matrix_market((d / "x.mtx").string(), Eigen::MatrixXd(2 * b));  // x = b, so the relative error is 1/2
  std::vector<std::string> args = {"closurelab", "deconvolve", "--matrix", (d / "A.mtx").string(), "--rhs",
                                   (d / "b.mtx").string(), "--x-true", (d / "x.mtx").string(), "--method", "tsvd",
                                   "--param", "k=2"};
  std::vector<char*> argv;
  for (auto& s : args) argv.push_back(s.data());
  std::stringstream out;
  auto* old = std::cout.rdbuf(out.rdbuf());
  const int rc = run_deconvolve_command(static_cast<int>(argv.size()), argv.data(), builtin_registry());
  std::cout.rdbuf(old);
  std::filesystem::remove_all(d);
  ASSERT_EQ(rc, 0);
  const json j = json::parse(out.str());
  EXPECT_EQ(j["status"], "converged");
  ASSERT_TRUE(j["relative_error"].is_number()) << j.dump();
  EXPECT_NEAR(j["relative_error"].get<double>(), 0.5, 1e-15);
  EXPECT_NEAR(j["stats"]["solution_norm"].get<double>() / (std::sqrt(5.0) * 1e200), 1.0, 1e-15);
}
