#include "core/io/matrix_market.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
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
  long v = 0;
  if (!(ss >> v)) r.fail(std::string("expected an integer ") + what);
  return v;
}

}  // namespace

MatrixMarketData read_matrix_market(const std::string& file) {
  LineReader r;
  r.file = file;
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
  if (symmetric && d.rows != d.cols) r.fail("a symmetric matrix must be square");
  if (d.coordinate) {
    const long nnz = parse_index(r, ss, "entry count");
    if (nnz < 0) r.fail("negative entry count");
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<size_t>(symmetric ? 2 * nnz : nnz));
    for (long k = 0; k < nnz; ++k) {
      if (!r.next(line)) r.fail("file ends after " + std::to_string(k) + " of " + std::to_string(nnz) + " entries");
      std::istringstream es(line);
      const long i = parse_index(r, es, "row index"), j = parse_index(r, es, "column index");
      if (i < 1 || i > d.rows || j < 1 || j > d.cols) r.fail("index (" + std::to_string(i) + ", " + std::to_string(j) + ") out of range");
      const double v = parse_value(r, es);
      t.emplace_back(i - 1, j - 1, v);
      if (symmetric && i != j) t.emplace_back(j - 1, i - 1, v);
    }
    d.sparse.resize(d.rows, d.cols);
    d.sparse.setFromTriplets(t.begin(), t.end());
    d.sparse.makeCompressed();
  } else {
    d.dense.resize(d.rows, d.cols);
    d.dense.setZero();
    // Column-major; symmetric stores the lower triangle only.
    for (Eigen::Index j = 0; j < d.cols; ++j)
      for (Eigen::Index i = symmetric ? j : 0; i < d.rows; ++i) {
        if (!r.next(line)) r.fail("file ends before all " + std::to_string(d.rows * d.cols) + " array entries");
        std::istringstream es(line);
        d.dense(i, j) = parse_value(r, es);
        if (symmetric) d.dense(j, i) = d.dense(i, j);
      }
  }
  if (r.next(line)) r.fail("unexpected extra data after the last entry");
  return d;
}

Eigen::VectorXd read_matrix_market_vector(const std::string& file) {
  const MatrixMarketData d = read_matrix_market(file);
  if (d.rows != 1 && d.cols != 1)
    throw ConfigError(file, "expected a vector (n x 1 or 1 x n), got " + std::to_string(d.rows) + " x " + std::to_string(d.cols));
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
  if (!out) throw ConfigError(file, "write failed");
}

void write_matrix_market(const std::string& file, const Eigen::SparseMatrix<double>& m) {
  std::ofstream out(file);
  if (!out) throw ConfigError(file, "cannot write the Matrix Market file");
  out << "%%MatrixMarket matrix coordinate real general\n% written by closurelab\n"
      << m.rows() << " " << m.cols() << " " << m.nonZeros() << "\n" << std::setprecision(17);
  for (int k = 0; k < m.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it)
      out << it.row() + 1 << " " << it.col() + 1 << " " << it.value() << "\n";
  if (!out) throw ConfigError(file, "write failed");
}

}  // namespace closurelab
