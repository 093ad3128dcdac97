#include "experiments/testproblems/stability_case.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/closure/deconvolver.hpp"
#include "core/base/errors.hpp"

namespace closurelab {

double condition_number(const ForwardOperator& a) {
  const Eigen::VectorXd s = Eigen::BDCSVD<Eigen::MatrixXd>(a.to_dense()).singularValues();
  if (s.size() == 0) return 0.0;
  const double lo = s(s.size() - 1);
  return lo > 0 ? s(0) / lo : std::numeric_limits<double>::infinity();
}

json run_stability_case(const IllPosedProblem& p, const StabilityCaseInput& in, const Registry& registry) {
  double noise_norm = 0.0;
  const Eigen::VectorXd b = add_noise(p.b_exact, in.noise, in.seed, noise_norm);
  // δ for the discrepancy principle is the noise level a user would know, ‖e‖₂ (not the discretization error
  // of A, which the data carry too since they are made without the inverse crime; see "data_discretization_error").
  const double delta = std::max(noise_norm, 1e-14 * p.b_exact.norm());
  const double xnorm = p.x_true.norm();
  auto rel_error = [&](const Eigen::VectorXd& x) { return (x - p.x_true).norm() / xnorm; };
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };

  json resolved;
  auto d = registry.deconvolvers.create(in.method, "/method", &resolved);
  d->setup(p.a);
  const DeconvolutionResult r = d->solve(b, delta);
  bool all_finite = r.x.allFinite() && std::isfinite(r.stats.residual_norm) && std::isfinite(r.stats.solution_norm);
  const double err = rel_error(r.x);

  json errors = {{"relative_error", num(err)},
                 {"chosen_parameter", num(r.stats.chosen_parameter)},
                 {"residual_norm", num(r.stats.residual_norm)},
                 {"delta", delta},
                 {"noise_norm", noise_norm},
                 {"data_discretization_error", (p.a.apply(p.x_true) - p.b_exact).norm() / p.b_exact.norm()}};
  if (in.scan_best) {
    double best = std::numeric_limits<double>::infinity(), best_param = 0.0;
    int visited = 0;
    // The best member is searched over the whole family: scan stops meant for the rules (CG's patience) are
    // lifted for this search.
    json scan_config = resolved;
    if (scan_config.contains("patience")) scan_config["patience"] = 1000000;
    auto full = registry.deconvolvers.create(scan_config, "/method");
    full->setup(p.a);
    full->scan(b, [&](const ScanPoint& s) {
      ++visited;
      const Eigen::VectorXd x = s.solution();
      if (!x.allFinite()) {
        all_finite = false;
        return true;
      }
      const double e = rel_error(x);
      if (e < best) {
        best = e;
        best_param = s.parameter;
      }
      return true;
    });
    errors["best_relative_error"] = num(best);
    errors["best_parameter"] = num(best_param);
    errors["scanned"] = visited;
    errors["ratio_to_best"] = num(err / best);
  }
  std::string status = "ok";
  if (r.status == DeconvolutionStatus::no_convergence) status = "no_convergence";
  if (r.status == DeconvolutionStatus::numerical_issue || !all_finite) status = "numerical_issue";
  json row = r.to_json();
  row["status"] = status;
  row["deconvolution_status"] = to_string(r.status);
  if (!r.stats.note.empty()) row["note"] = r.stats.note;  // the rule chose at the edge of its scan
  row["errors"] = errors;
  row["all_finite"] = all_finite;
  row["method_resolved"] = resolved;
  row["problem"] = p.info;
  row["problem"]["name"] = p.name;
  row["condition_number"] = num(condition_number(p.a));
  row["noise"] = in.noise;
  row["seed"] = in.seed;
  return row;
}

}  // namespace closurelab
