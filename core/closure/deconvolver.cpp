#include "core/closure/deconvolver.hpp"

#include <cmath>

#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"

namespace closurelab {


json DeconvolutionResult::to_json() const {
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json j{{"status", to_string(status)},
         {"stats",
          {{"iterations", stats.iterations},
           {"residual_norm", num(stats.residual_norm)},
           {"solution_norm", num(stats.solution_norm)},
           {"chosen_parameter", num(stats.chosen_parameter)},
           {"parameter_name", stats.parameter_name},
           {"rule", stats.rule},
           {"message", stats.message}}},
         {"cost",
          {{"matvecs", cost.matvecs}, {"setup_seconds", cost.setup_seconds}, {"solve_seconds", cost.solve_seconds}}}};
  if (!stats.note.empty()) j["stats"]["note"] = stats.note;  // only when there is one (older tables have none)
  return j;
}

Eigen::MatrixXd Deconvolver::solve_columns(const Eigen::MatrixXd& B, double noise_level,
                                           std::vector<DeconvolutionResult>* results) const {
  Eigen::MatrixXd X;
  for (Eigen::Index k = 0; k < B.cols(); ++k) {
    DeconvolutionResult r = solve(B.col(k), noise_level);
    if (k == 0) X.resize(r.x.size(), B.cols());
    X.col(k) = r.x;
    if (results) {
      r.x.resize(0);
      results->push_back(std::move(r));
    }
  }
  return X;
}

void check_solve_input(const ForwardOperator& A, const Eigen::VectorXd& b, double noise_level) {
  if (b.size() != A.rows())
    throw ConfigError("/rhs", "right-hand side has " + std::to_string(b.size()) + " entries but the operator has " +
                                  std::to_string(A.rows()) + " rows");
  for (Eigen::Index i = 0; i < b.size(); ++i)
    if (!std::isfinite(b(i))) throw ConfigError("/rhs", "right-hand side entry " + std::to_string(i) + " is not finite");
  if (!std::isfinite(noise_level) || noise_level < 0)
    throw ConfigError("/noise_level", "noise level must be finite and >= 0, got " + std::to_string(noise_level));
}

}  // namespace closurelab
