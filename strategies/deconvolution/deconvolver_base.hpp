#pragma once
// Shared plumbing of the built-in deconvolvers: the parameter rule, timing of setup and solve, input checks,
// and the final NaN/Inf guard. A strategy implements its setup, its fixed-parameter solve and its scan.
#include <chrono>
#include <cmath>
#include <string>

#include "core/closure/deconvolver.hpp"
#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/parameter_choice.hpp"

namespace closurelab {

struct RuleConfig {
  ParameterRule rule = ParameterRule::fixed;
  double safety = 1.01;  // τ of the discrepancy principle

  static RuleConfig from_json(const json& p) {
    return RuleConfig{parse_parameter_rule(p.at("rule").get<std::string>(), "/rule"), p.at("safety").get<double>()};
  }
};

class DeconvolverBase : public Deconvolver {
 public:
  DeconvolverBase(std::string name, RuleConfig rule, std::string parameter_name)
      : name_(std::move(name)), rule_(rule), parameter_name_(std::move(parameter_name)) {}
  std::string name() const override { return name_; }

  void setup(const ForwardOperator& a) final {
    const auto t0 = std::chrono::steady_clock::now();
    a_ = &a;
    do_setup(a);
    setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  DeconvolutionResult solve(const Eigen::VectorXd& b, double noise_level = 0.0) const final {
    require_setup();
    check_solve_input(*a_, b, noise_level);
    const auto t0 = std::chrono::steady_clock::now();
    DeconvolutionResult r =
        rule_.rule == ParameterRule::fixed ? solve_fixed(b) : choose_by_rule(*this, b, rule_.rule, noise_level, rule_.safety);
    r.stats.rule = to_string(rule_.rule);
    r.stats.parameter_name = parameter_name_;
    r.cost.setup_seconds = setup_seconds_;
    r.cost.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.x.allFinite()) {
      r.status = DeconvolutionStatus::numerical_issue;
      r.stats.message = "non-finite entries in the solution" + (r.stats.message.empty() ? "" : "; " + r.stats.message);
    }
    return r;
  }

  void scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const final {
    require_setup();
    check_solve_input(*a_, b, 0.0);
    do_scan(b, visit);
  }

 protected:
  virtual void do_setup(const ForwardOperator& a) = 0;
  virtual DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const = 0;
  virtual void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const = 0;

  const ForwardOperator& op() const { return *a_; }
  const RuleConfig& rule() const { return rule_; }
  // Fills the norms of a fixed-parameter result from its x (one more product with A).
  void finish_fixed(DeconvolutionResult& r, const Eigen::VectorXd& b, double parameter) const {
    r.stats.residual_norm = (b - a_->apply(r.x)).norm();
    r.stats.solution_norm = r.x.norm();
    r.stats.chosen_parameter = parameter;
    r.cost.matvecs += 1;
  }

 private:
  void require_setup() const {
    if (!a_) throw ConfigError("", name_ + ": solve() called before setup(A)");
  }
  std::string name_;
  RuleConfig rule_;
  std::string parameter_name_;
  const ForwardOperator* a_ = nullptr;
  double setup_seconds_ = 0.0;
};

// The schema entries every strategy shares.
inline ParamSpec rule_param(std::vector<std::string> allowed, std::string def) {
  return string_param("rule", std::move(def), "parameter-choice rule", std::move(allowed));
}
inline ParamSpec safety_param() {
  return number_param("safety", 1.01, "discrepancy-principle safety factor tau (stop when ||b - A x|| <= tau delta)", 1.0,
                      10.0);
}

// The result of a fixed-parameter run from the scan member that ends it (x, norms, parameter, cost, issue).
inline DeconvolutionResult result_from_scan_point(const ScanPoint& p) {
  DeconvolutionResult r;
  r.x = p.solution();
  r.stats.residual_norm = p.residual_norm;
  r.stats.solution_norm = p.solution_norm;
  r.stats.chosen_parameter = p.parameter;
  r.stats.iterations = static_cast<int>(p.parameter);
  r.cost.matvecs = p.matvecs;
  if (!p.issue.empty()) {
    r.status = DeconvolutionStatus::numerical_issue;
    r.stats.message = p.issue;
  }
  return r;
}

}  // namespace closurelab
