#pragma once
// Parameter-choice rules for the regularized families of every deconvolver (§4.2: "the choice of truncation
// is determined by the actual level of noise in the right hand side"):
//   fixed        the configured parameter;
//   discrepancy  the most regularized member with ‖b − A x‖ <= τ δ (Morozov; τ ≈ 1.01, δ = ‖noise‖₂);
//   gcv          the minimizer of the generalized cross-validation function ‖r‖² / (m − trace(influence))²;
//   lcurve       the corner of the log‖r‖–log‖x‖ curve (the sharpest turn of its convex hull facing the origin);
//                for a method that penalizes a seminorm ‖Lx‖ (general-form Tikhonov) the curve is log‖r‖–log‖Lx‖
//                (Hansen's L-curve of the functional the method minimizes).
// The chooser consumes the ScanPoints a Deconvolver::scan visits (most regularized first).
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "core/base/enum_names.hpp"
#include "core/closure/deconvolver.hpp"

namespace closurelab {

enum class ParameterRule { fixed, discrepancy, gcv, lcurve };
template <>
struct EnumNames<ParameterRule> {
  static constexpr std::array<std::pair<ParameterRule, std::string_view>, 4> table{
      {{ParameterRule::fixed, "fixed"},
       {ParameterRule::discrepancy, "discrepancy"},
       {ParameterRule::gcv, "gcv"},
       {ParameterRule::lcurve, "lcurve"}}};
};
inline ParameterRule parse_parameter_rule(const std::string& s, const std::string& path) {
  return parse_name<ParameterRule>(s, path);
}
inline std::string to_string(ParameterRule r) { return name_of(r); }

// A recorded scan point (norms only; the solution is recomputed for the chosen one).
struct RecordedPoint {
  double parameter = 0.0, residual_norm = 0.0, solution_norm = 0.0, gcv = -1.0;
};

// Walks `scan` and picks a member by `rule` (not `fixed`). For the discrepancy principle the walk stops at the
// first member that satisfies it (status converged) or ends at the last one (status no_convergence).
// For gcv/lcurve the whole family is scanned, then scanned again up to the chosen member to get its x.
// A scan point reporting an issue ends the walk there with status numerical_issue. Fills x, status, stats.{residual_norm, solution_norm,
// chosen_parameter, iterations (points visited), rule, message}. `lcurve_seminorm`, when given, is the L-curve's
// ordinate x -> ‖Lx‖ in place of ‖x‖ (the result's solution_norm stays ‖x‖).
// A choice at the edge of the scan fills stats.note (the status stays as it is): gcv or lcurve choosing the first
// or the last member of the family scanned, [lo, hi] the scanned range, or the discrepancy principle met already by
// the first (most regularized) member; the rule's own optimum may then lie beyond the scan. `parameter_name` names
// the parameter in that note ("alpha", "k", ...).
using Seminorm = std::function<double(const Eigen::VectorXd&)>;
DeconvolutionResult choose_by_rule(const Deconvolver& d, const Eigen::VectorXd& b, ParameterRule rule,
                                   double noise_level, double safety, const Seminorm& lcurve_seminorm = {},
                                   const std::string& parameter_name = "parameter");

// Index of the L-curve corner among points, most regularized first (see the .cpp); -1 if there are none.
int lcurve_corner(const std::vector<RecordedPoint>& points);

// Geometric grid of `count` values from hi down to lo (most regularized first for α).
std::vector<double> log_grid_descending(double hi, double lo, int count);

}  // namespace closurelab
