#include "core/io/matrix_market.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

#include "core/base/errors.hpp"

namespace closurelab {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

struct LineReader {
  std::ifstream in;
  std::string file;
  int line_no = 0;
  // Next non-comment, non-blank line; false at end of file.
  bool next(std::string& line) {
    while (std::getline(in, line)) {
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const auto first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == '%') continue;
      return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw ConfigError(file, "line " + std::to_string(line_no) + ": " + what);
  }
};

double parse_value(LineReader& r, std::istringstream& ss) {
  std::string tok;
  if (!(ss >> tok)) r.fail("missing value");
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str() || *end != '\0') r.fail("'" + tok + "' is not a number");
  if (!std::isfinite(v)) r.fail("non-finite value '" + tok + "'");
  return v;
}

long parse_index(LineReader& r, std::istringstream& ss, const char* what) {
  std::string tok;
  if (!(ss >> tok)) r.fail(std::string("expected an integer ") + what);
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(tok.c_str(), &end, 10);
  if (end == tok.c_str() || *end != '\0' || errno == ERANGE)
    r.fail(std::string("expected an integer ") + what + ", got '" + tok + "'");
  return v;
}

// Every data line holds exactly the expected tokens (a lax reader silently drops a misplaced column).
void expect_line_end(LineReader& r, std::istringstream& ss) {
  std::string extra;
  if (ss >> extra) r.fail("unexpected extra token '" + extra + "'");
}

double parse_entry(LineReader& r, std::istringstream& ss, bool integer_field) {
  const double v = parse_value(r, ss);
  if (integer_field && v != std::floor(v)) r.fail("non-integer value in an integer matrix");
  expect_line_end(r, ss);
  return v;
}

}  // namespace

MatrixMarketData read_matrix_market(const std::string& file) {
  LineReader r;
  r.file = file;
  // A regular file of bounded size (a device such as /dev/zero would be read until memory runs out); the
  // declared sizes are checked against the file's bytes before anything is allocated.
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw ConfigError(file, "cannot open the Matrix Market file (no such file)");
  if (!std::filesystem::is_regular_file(file, ec)) throw ConfigError(file, "not a regular file");
  const auto bytes = static_cast<long>(std::filesystem::file_size(file, ec));
  if (ec) throw ConfigError(file, "cannot read the file size: " + ec.message());
  if (bytes > kMatrixMarketMaxBytes)
    throw ConfigError(file, "file of " + std::to_string(bytes) + " bytes exceeds the reader's limit of " +
                                std::to_string(kMatrixMarketMaxBytes) + " bytes");
  r.in.open(file);
  if (!r.in) throw ConfigError(file, "cannot open the Matrix Market file");
  std::string banner;
  if (!std::getline(r.in, banner)) throw ConfigError(file, "empty file (expected a %%MatrixMarket banner)");
  r.line_no = 1;
  std::istringstream bs(lower(banner));
  std::string tag, object, format, field, symmetry;
  bs >> tag >> object >> format >> field >> symmetry;
  if (tag != "%%matrixmarket") r.fail("missing %%MatrixMarket banner");
  if (object != "matrix") r.fail("unsupported object '" + object + "' (only matrix)");
  if (format != "coordinate" && format != "array") r.fail("unsupported format '" + format + "' (coordinate or array)");
  if (field != "real" && field != "integer" && field != "double")
    r.fail("unsupported field '" + field + "' (real or integer)");
  if (symmetry != "general" && symmetry != "symmetric")
    r.fail("unsupported symmetry '" + symmetry + "' (general or symmetric)");
  const bool symmetric = symmetry == "symmetric";

  std::string line;
  if (!r.next(line)) r.fail("missing size line");
  std::istringstream ss(line);
  MatrixMarketData d;
  d.coordinate = format == "coordinate";
  d.rows = parse_index(r, ss, "row count");
  d.cols = parse_index(r, ss, "column count");
  if (d.rows <= 0 || d.cols <= 0) r.fail("matrix dimensions must be positive");
  if (d.rows > kMatrixMarketMaxDimension || d.cols > kMatrixMarketMaxDimension)
    r.fail("dimensions " + std::to_string(d.rows) + " x " + std::to_string(d.cols) + " exceed the reader's limit of " +
           std::to_string(kMatrixMarketMaxDimension) + " rows or columns");
  if (symmetric && d.rows != d.cols) r.fail("a symmetric matrix must be square");
  const bool integer_field = field == "integer";
  if (d.coordinate) {
    const long nnz = parse_index(r, ss, "entry count");
    expect_line_end(r, ss);
    if (nnz < 0) r.fail("negative entry count");
    // An entry line "i j v\n" takes at least 6 bytes.
    if (nnz > bytes / 6)
      r.fail("declares " + std::to_string(nnz) + " entries but the file has only " + std::to_string(bytes) + " bytes");
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<size_t>(symmetric ? 2 * nnz : nnz));
    for (long k = 0; k < nnz; ++k) {
      if (!r.next(line)) r.fail("file ends after " + std::to_string(k) + " of " + std::to_string(nnz) + " entries");
      std::istringstream es(line);
      const long i = parse_index(r, es, "row index"), j = parse_index(r, es, "column index");
      if (i < 1 || i > d.rows || j < 1 || j > d.cols)
        r.fail("index (" + std::to_string(i) + ", " + std::to_string(j) + ") out of range");
      const double v = parse_entry(r, es, integer_field);
      t.emplace_back(i - 1, j - 1, v);
      if (symmetric && i != j) t.emplace_back(j - 1, i - 1, v);
    }
    d.sparse.resize(d.rows, d.cols);
    d.sparse.setFromTriplets(t.begin(), t.end());
    d.sparse.makeCompressed();
  } else {
    expect_line_end(r, ss);
    // An array entry "v\n" takes at least 2 bytes (symmetric: the lower triangle only).
    const long budget = bytes / 2;
    const long needed_per_col = symmetric ? (d.rows + 1) / 2 : d.rows;
    if (d.cols > budget / std::max(needed_per_col, 1L))
      r.fail("declares a " + std::to_string(d.rows) + " x " + std::to_string(d.cols) + " array but the file has only " +
             std::to_string(bytes) + " bytes");
    d.dense.resize(d.rows, d.cols);
    d.dense.setZero();
    // Column-major; symmetric stores the lower triangle only.
    for (Eigen::Index j = 0; j < d.cols; ++j)
      for (Eigen::Index i = symmetric ? j : 0; i < d.rows; ++i) {
        if (!r.next(line)) r.fail("file ends before all " + std::to_string(d.rows * d.cols) + " array entries");
        std::istringstream es(line);
        d.dense(i, j) = parse_entry(r, es, integer_field);
        if (symmetric) d.dense(j, i) = d.dense(i, j);
      }
  }
  if (r.next(line)) r.fail("unexpected extra data after the last entry");
  return d;
}

Eigen::VectorXd read_matrix_market_vector(const std::string& file) {
  const MatrixMarketData d = read_matrix_market(file);
  if (d.rows != 1 && d.cols != 1)
    throw ConfigError(
        file, "expected a vector (n x 1 or 1 x n), got " + std::to_string(d.rows) + " x " + std::to_string(d.cols));
  const Eigen::MatrixXd m = d.to_dense();
  return d.cols == 1 ? Eigen::VectorXd(m.col(0)) : Eigen::VectorXd(m.row(0).transpose());
}

void write_matrix_market(const std::string& file, const Eigen::MatrixXd& m) {
  std::ofstream out(file);
  if (!out) throw ConfigError(file, "cannot write the Matrix Market file");
  out << "%%MatrixMarket matrix array real general\n% written by closurelab\n" << m.rows() << " " << m.cols() << "\n";
  out << std::setprecision(17);
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i) out << m(i, j) << "\n";
  out.close();  // the buffer's last write fails here (a full disk, /dev/full), not before
  if (!out) throw ConfigError(file, "write failed (disk full or device error)");
}

void write_matrix_market(const std::string& file, const Eigen::SparseMatrix<double>& m) {
  std::ofstream out(file);
  if (!out) throw ConfigError(file, "cannot write the Matrix Market file");
  out << "%%MatrixMarket matrix coordinate real general\n% written by closurelab\n"
      << m.rows() << " " << m.cols() << " " << m.nonZeros() << "\n"
      << std::setprecision(17);
  for (int k = 0; k < m.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it)
      out << it.row() + 1 << " " << it.col() + 1 << " " << it.value() << "\n";
  out.close();  // the buffer's last write fails here (a full disk, /dev/full), not before
  if (!out) throw ConfigError(file, "write failed (disk full or device error)");
}

}  // namespace closurelab
