#pragma once
// A small Matrix Market reader/writer (NIST format, https://math.nist.gov/MatrixMarket/formats.html) for
// `closurelab deconvolve`: "%%MatrixMarket matrix coordinate|array real|integer general|symmetric".
// Errors (missing file, bad banner, unsupported field/symmetry, wrong counts, indices out of range, non-numeric
// or non-finite entries, extra tokens, a fractional value in an integer matrix, sizes the file cannot hold)
// throw ConfigError naming the file and the line.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

namespace closurelab {

// The reader refuses larger files (and anything that is not a regular file) before reading.
inline constexpr long kMatrixMarketMaxBytes = 1L << 31;  // 2 GiB
// And larger dimensions: a coordinate matrix's index arrays grow with its declared rows and columns, not with its
// entries (a 7.9e9 x 1 header with one entry asked for ~95 GB), and Eigen's sparse indices are 32-bit. At this
// limit they take at most ~0.4 GB.
inline constexpr long kMatrixMarketMaxDimension = 1L << 24;  // 16,777,216

struct MatrixMarketData {
  bool coordinate = false;             // coordinate (sparse) or array (dense) format
  Eigen::SparseMatrix<double> sparse;  // coordinate format
  Eigen::MatrixXd dense;               // array format
  Eigen::Index rows = 0, cols = 0;
  Eigen::MatrixXd to_dense() const { return coordinate ? Eigen::MatrixXd(sparse) : dense; }
};

MatrixMarketData read_matrix_market(const std::string& file);
// A vector: an n×1 or 1×n matrix in either format.
Eigen::VectorXd read_matrix_market_vector(const std::string& file);

void write_matrix_market(const std::string& file, const Eigen::MatrixXd& m);              // array real general
void write_matrix_market(const std::string& file, const Eigen::SparseMatrix<double>& m);  // coordinate real general

}  // namespace closurelab
