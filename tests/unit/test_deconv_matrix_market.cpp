// Matrix Market I/O: round trips in both formats, symmetric storage, and a clear error for each kind of
// malformed file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/base/errors.hpp"
#include "core/io/matrix_market.hpp"

using namespace closurelab;

namespace {
std::string temp_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("closurelab_mm_" + name);
  std::ofstream(p) << text;
  return p.string();
}
std::string error_of(const std::string& file) {
  try {
    read_matrix_market(file);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(DeconvMatrixMarket, RoundTripsDenseAndSparse) {
  Eigen::MatrixXd m(3, 2);
  m << 1.5, -2, 0, 1e-300, 3.25, 7;
  const std::string f = temp_file("dense.mtx", "");
  write_matrix_market(f, m);
  const MatrixMarketData d = read_matrix_market(f);
  EXPECT_FALSE(d.coordinate);
  EXPECT_EQ(d.to_dense(), m);  // 17 significant digits: exact

  Eigen::SparseMatrix<double> s = m.sparseView();
  write_matrix_market(f, s);
  const MatrixMarketData e = read_matrix_market(f);
  EXPECT_TRUE(e.coordinate);
  EXPECT_EQ(e.to_dense(), m);
}

TEST(DeconvMatrixMarket, ReadsSymmetricCoordinateAndArrayAndVectors) {
  const auto c = read_matrix_market(temp_file(
      "sym.mtx", "%%MatrixMarket matrix coordinate real symmetric\n% comment\n3 3 4\n1 1 2\n2 1 -1\n2 2 2\n3 3 5\n"));
  Eigen::MatrixXd want(3, 3);
  want << 2, -1, 0, -1, 2, 0, 0, 0, 5;
  EXPECT_EQ(c.to_dense(), want);
  const auto a =
      read_matrix_market(temp_file("syma.mtx", "%%MatrixMarket matrix array real symmetric\n3 3\n2\n-1\n0\n2\n0\n5\n"));
  EXPECT_EQ(a.to_dense(), want);
  const Eigen::VectorXd v =
      read_matrix_market_vector(temp_file("vec.mtx", "%%MatrixMarket matrix array integer general\n3 1\n1\n2\n3\n"));
  EXPECT_EQ(v, Eigen::Vector3d(1, 2, 3));
}

TEST(DeconvMatrixMarket, MalformedFilesGiveClearErrors) {
  // Each malformed file's error names what is wrong.
  const auto error_names = [](const std::string& name, const std::string& content, const std::string& fragment) {
    EXPECT_NE(error_of(temp_file(name, content)).find(fragment), std::string::npos) << name;
  };
  EXPECT_NE(error_of("/nonexistent/dir/a.mtx").find("cannot open"), std::string::npos);
  error_names("nobanner.mtx", "3 3\n1\n", "banner");
  error_names("complex.mtx", "%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n", "field");
  error_names("range.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1\n", "out of range");
  error_names("short.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 1\n", "ends after");
  error_names("nan.mtx", "%%MatrixMarket matrix array real general\n1 1\nnan\n", "non-finite");
  error_names("word.mtx", "%%MatrixMarket matrix array real general\n1 1\nabc\n", "not a number");
  error_names("extra.mtx", "%%MatrixMarket matrix array real general\n1 1\n1\n2\n", "extra");
  // A header the fuzzer found: 7.9e9 rows and one entry (the index arrays alone would take ~95 GB).
  error_names("tall.mtx", "%%MatrixMarket matrix coordinate real general\n7879747974 1 1\n1 1 1\n",
              "exceed the reader's limit");
  error_names("wide.mtx", "%%MatrixMarket matrix coordinate real general\n1 16777217 1\n1 1 1\n",
              "exceed the reader's limit");
  EXPECT_THROW(
      read_matrix_market_vector(temp_file("mat.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n")),
      ConfigError);
}
