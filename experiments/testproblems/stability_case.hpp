#pragma once
// One case of the hard-case stability suite: a test problem, a noise level and a deconvolver with a
// parameter rule. Reports the rule's error next to the best error over the method's whole regularized family
// (found by walking Deconvolver::scan — the same family the rule chooses from), their ratio, the condition
// number of A, finiteness of every output, status, statistics and cost. Shared by the gtests and the
// "deconvolution_stability" experiment kind so both measure the same thing.
#include <cstdint>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "experiments/testproblems/ill_posed_problems.hpp"

namespace closurelab {

struct StabilityCaseInput {
  double noise = 0.0;          // relative noise ‖e‖/‖b‖
  std::uint64_t seed = 12345;  // RNG seed of the noise
  json method;                 // deconvolver config {"name": ..., "rule": ..., ...}
  bool scan_best = true;       // also scan the family for the best parameter
};

// Row with "errors" {relative_error, best_relative_error, ratio_to_best, best_parameter, ...}, "stats",
// "cost", "status" ("ok", "no_convergence", "numerical_issue"), "problem", "condition_number", "all_finite".
// δ passed to the rule is the noise norm ‖e‖₂ (at least 1e-14‖b‖, so noise-free cases have a tiny positive δ),
// recorded as "delta"; the discretization error ‖A x_true − b_exact‖/‖b_exact‖ is recorded next to it.
json run_stability_case(const IllPosedProblem& problem, const StabilityCaseInput& in, const Registry& registry);

// κ₂(A) = σ_max/σ_min from a dense SVD (σ_min may be at rounding level: κ then reads ~1e16 or more).
double condition_number(const ForwardOperator& a);

}  // namespace closurelab
