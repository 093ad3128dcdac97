#pragma once
// The deconvolution strategy family (DESIGN.md §2, paper §4): given a forward operator A (a discretization of
// R_η (4.1), §4.2) and averages b, a regularized solution of A x = b (4.8).
//
// Configuration is separated from the instance bound to one problem: the factory takes resolved JSON,
// `setup(A)` does the factorizations once, `solve(b, δ)` is cheap and returns a DeconvolutionResult value
// (status, statistics, cost); non-convergence is a result, bad configuration a ConfigError.
//
// Every strategy is a one-parameter family of regularized solutions x(p) (α, truncation index, iteration
// count or series order). `scan` visits that family from the most to the least regularized member; the
// parameter-choice rules (core/closure/parameter_choice.hpp) and the stability suite's "best parameter" search both
// walk that same scan, so a rule never has a second code path.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/status.hpp"

namespace closurelab {

class ForwardOperator;

// The shared status vocabulary (core/base/status.hpp); a deconvolution never ends at a target time.
using DeconvolutionStatus = Status;

struct DeconvolutionStats {
  int iterations = 0;              // iterations / series order / number of scanned parameters
  double residual_norm = 0.0;      // ‖b − A x‖₂
  double solution_norm = 0.0;      // ‖x‖₂
  double chosen_parameter = 0.0;   // α, truncation index, iteration count or order
  std::string parameter_name;      // "alpha", "k", "iterations", "order"
  std::string rule;                // "fixed", "discrepancy", "gcv", "lcurve"
  std::string message;             // why the status is not `converged`, or a note
  std::string note;                // a warning that leaves the status as it is: a rule's choice at the edge of
                                   // its scan (core/closure/parameter_choice.hpp); empty otherwise
};

struct DeconvolutionCost {
  long matvecs = 0;                // products with A or Aᵀ (a Kronecker product counts as one)
  double setup_seconds = 0.0;      // factorizations in setup()
  double solve_seconds = 0.0;
};

struct DeconvolutionResult {
  Eigen::VectorXd x;
  DeconvolutionStatus status = DeconvolutionStatus::converged;
  DeconvolutionStats stats;
  DeconvolutionCost cost;
  json to_json() const;  // everything except x
};

// One member of a strategy's regularized family, as visited by Deconvolver::scan.
struct ScanPoint {
  double parameter = 0.0;
  double residual_norm = 0.0;          // ‖b − A x‖₂
  double solution_norm = 0.0;          // ‖x‖₂
  double gcv = -1.0;                   // GCV function value where the method can compute it, else < 0; up to a
                                       // positive factor common to one scan (badly scaled data are scanned scaled)
  long matvecs = 0;                    // products with A or Aᵀ spent so far in this scan
  bool last = false;                   // no further member will be visited
  std::string issue;                   // non-empty: a numerical issue detected here (e.g. a growing mode)
  std::function<Eigen::VectorXd()> solution;  // x of this member; valid during the visit only
};
// Return false to stop the scan.
using ScanVisitor = std::function<bool(const ScanPoint&)>;

class Deconvolver {
 public:
  virtual ~Deconvolver() = default;
  virtual std::string name() const = 0;
  // Binds the instance to A and does the factorizations. Throws ConfigError when the configuration does not
  // fit the operator (e.g. a truncation index beyond the rank); A must outlive the instance.
  virtual void setup(const ForwardOperator& A) = 0;
  // Regularized solution by the configured parameter rule; `noise_level` δ = ‖b − b_exact‖₂ (absolute)
  // is used by the discrepancy principle. Throws ConfigError on wrong sizes or non-finite data.
  virtual DeconvolutionResult solve(const Eigen::VectorXd& b, double noise_level = 0.0) const = 0;
  // Visits the regularized family from most to least regularized (see the header comment).
  virtual void scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const = 0;
  // The solve of every column of B: X.col(k) = solve(B.col(k), noise_level).x, each column's result (its x left
  // empty) appended to `results` when given. For precomputing a closure that is linear in its data as a map (probing
  // it on unit data): a strategy with a factorisation and a fixed parameter does it by matrix products (the same
  // arithmetic as its one-column solve, to round-off), the default column by column.
  virtual Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& B, double noise_level = 0.0,
                                        std::vector<DeconvolutionResult>* results = nullptr) const;
};

// Shared input checks: sizes and finiteness of b and δ (ConfigError naming what is wrong).
void check_solve_input(const ForwardOperator& A, const Eigen::VectorXd& b, double noise_level);

}  // namespace closurelab
