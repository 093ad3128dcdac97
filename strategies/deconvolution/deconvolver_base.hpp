#pragma once
// Shared plumbing of the built-in deconvolvers: the parameter rule, timing of setup and solve, input checks,
// the scaling of badly scaled operators, and the final guards: an empty or non-finite x, or a nonzero x that fits
// the data no better than x = 0 (‖b − A x‖ >= ‖b‖), is never `converged`.
// A strategy implements its setup, its fixed-parameter solve and its scan.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "core/closure/deconvolver.hpp"
#include "core/base/errors.hpp"
#include "core/base/metrics.hpp"
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
    scaled_.reset();
    scale_exponent_ = 0;
    if (scale_invariant()) {
      // A = 2^k A' with max|A'| in [1/2, 1): the strategy solves A' x' = b and x = 2^-k x' (exact powers of
      // two, so a well-scaled operator (|k| <= 32) is used as given, bit for bit).
      const int k = max_entry_exponent(a);
      if (std::abs(k) > 32) {
        scaled_ = scaled_operator(a, -k);
        scale_exponent_ = k;
        a_ = &*scaled_;
      }
    }
    do_setup(*a_);
    setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  DeconvolutionResult solve(const Eigen::VectorXd& b, double noise_level = 0.0) const final {
    require_setup();
    check_solve_input(*a_, b, noise_level);
    const auto t0 = std::chrono::steady_clock::now();
    DeconvolutionResult r;
    if (rule_.rule == ParameterRule::fixed) {
      const int m = data_exponent(b);
      r = solve_fixed(m == 0 ? b : times_power_of_two(b, -m));
      unscale(r, m);
    } else {
      r = choose_by_rule(*this, b, rule_.rule, noise_level, rule_.safety, lcurve_seminorm(),
                         parameter_name_);  // through scan(): already unscaled
      const std::string hint = scan_hint();
      if (!r.stats.note.empty() && !hint.empty()) r.stats.note += " (" + hint + ")";
    }
    finish_solve(r, b, noise_level, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    return r;
  }

  // Columns at once where the strategy offers it (solve_fixed_columns) for a fixed parameter on a well-scaled
  // problem, each column's norms from one product A X and the guards of solve(); else one solve per column.
  Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& B, double noise_level = 0.0,
                                std::vector<DeconvolutionResult>* results = nullptr) const final {
    require_setup();
    bool batched = rule_.rule == ParameterRule::fixed && scale_exponent_ == 0;
    for (Eigen::Index k = 0; k < B.cols() && batched; ++k) {
      check_solve_input(*a_, B.col(k), noise_level);
      batched = data_exponent(B.col(k)) == 0;
    }
    const auto t0 = std::chrono::steady_clock::now();
    FixedColumns fc;
    if (batched) fc = solve_fixed_columns(B);
    if (fc.x.cols() != B.cols() || fc.x.rows() != a_->cols()) return Deconvolver::solve_columns(B, noise_level, results);
    const Eigen::MatrixXd residual = B - apply_to_columns(fc.x);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() /
                           static_cast<double>(std::max<Eigen::Index>(B.cols(), 1));
    for (Eigen::Index k = 0; k < B.cols(); ++k) {
      DeconvolutionResult r;
      r.x = fc.x.col(k);
      r.stats.residual_norm = robust_norm(residual.col(k));
      r.stats.solution_norm = robust_norm(r.x);
      r.stats.chosen_parameter = fc.parameter;
      r.cost.matvecs = fc.matvecs_per_column + 1;
      if (!fc.issue.empty()) {
        r.status = DeconvolutionStatus::numerical_issue;
        r.stats.message = fc.issue;
      }
      finish_solve(r, B.col(k), noise_level, seconds);
      fc.x.col(k) = r.x;
      if (results) {
        r.x.resize(0);
        results->push_back(std::move(r));
      }
    }
    return std::move(fc.x);
  }

 protected:
  // A fixed-parameter solve of many right-hand sides: x (empty where the strategy has nothing faster than one
  // solve per column), its parameter, the products with A or Aᵀ one column costs, and an issue common to all.
  struct FixedColumns {
    Eigen::MatrixXd x;
    double parameter = 0.0;
    long matvecs_per_column = 0;
    std::string issue;
  };
  virtual FixedColumns solve_fixed_columns(const Eigen::MatrixXd& /*B*/) const { return {}; }

 private:
  Eigen::MatrixXd apply_to_columns(const Eigen::MatrixXd& x) const {  // A X: one product where A is dense
    if (a_->storage() == OperatorStorage::dense) return a_->dense() * x;
    Eigen::MatrixXd out(a_->rows(), x.cols());
    for (Eigen::Index k = 0; k < x.cols(); ++k) out.col(k) = a_->apply(x.col(k));
    return out;
  }
  // The statistics and guards every solve ends with: an x of the wrong size, non-finite, or no better than x = 0.
  void finish_solve(DeconvolutionResult& r, const Eigen::VectorXd& b, double noise_level, double seconds) const {
    r.stats.rule = to_string(rule_.rule);
    r.stats.parameter_name = parameter_name_;
    r.cost.setup_seconds = setup_seconds_;
    r.cost.solve_seconds = seconds;
    if (r.x.size() != a_->cols()) {
      r.status = DeconvolutionStatus::numerical_issue;
      r.stats.message = name_ + " returned a solution of size " + std::to_string(r.x.size()) + " for " +
                        std::to_string(a_->cols()) + " unknowns" + (r.stats.message.empty() ? "" : "; " + r.stats.message);
      r.x = Eigen::VectorXd::Zero(a_->cols());
    } else if (!r.x.allFinite()) {
      r.status = DeconvolutionStatus::numerical_issue;
      r.stats.message = "non-finite entries in the solution" + (r.stats.message.empty() ? "" : "; " + r.stats.message);
    } else if (r.status == DeconvolutionStatus::converged &&
               !(rule_.rule == ParameterRule::discrepancy && r.stats.residual_norm <= rule_.safety * noise_level)) {
      no_better_than_zero(r, b);  // (data that are all noise meet the discrepancy principle near x = 0: kept)
    }
  }

 public:

  void scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const final {
    require_setup();
    check_solve_input(*a_, b, 0.0);
    const int m = data_exponent(b), xs = m - scale_exponent_;  // x = 2^xs x', r = 2^m r'
    if (m == 0 && scale_exponent_ == 0) return do_scan(b, visit);
    do_scan(m == 0 ? b : times_power_of_two(b, -m), [&](const ScanPoint& p) {  // members of the original problem
      ScanPoint q = p;
      q.parameter = unscale_parameter(p.parameter);
      q.residual_norm = std::ldexp(p.residual_norm, m);
      q.solution_norm = std::ldexp(p.solution_norm, xs);
      // q.gcv stays in the scaled problem's units: a factor 2^(2m) common to the whole scan, which leaves its
      // minimizer as it is, and which would overflow for data of 1e200 (the rule then found no finite GCV value).
      q.solution = [&p, xs] { return times_power_of_two(p.solution(), xs); };
      return visit(q);
    });
  }

 protected:
  virtual void do_setup(const ForwardOperator& a) = 0;
  virtual DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const = 0;
  virtual void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const = 0;

  const ForwardOperator& op() const { return *a_; }  // the (possibly rescaled) operator the strategy solves with
  // False for a method whose answer is not invariant under A -> cA (the Landweber series (4.3) assumes A ~ I).
  virtual bool scale_invariant() const { return true; }
  // op() = 2^-k A: a parameter given for A is converted with k (e.g. Tikhonov's alpha by 4^-k), and a scanned
  // one back with unscale_parameter.
  int scale_exponent() const { return scale_exponent_; }
  virtual double unscale_parameter(double p) const { return p; }
  const RuleConfig& rule() const { return rule_; }
  // The L-curve's ordinate when the method penalizes a seminorm ‖Lx‖ rather than ‖x‖ (empty: ‖x‖).
  virtual Seminorm lcurve_seminorm() const { return {}; }
  // Why a solution may fit no better than x = 0 with this method (appended to that message).
  virtual std::string no_fit_hint() const { return ""; }
  // Which parameters bound the rules' scan (appended to the note of a choice at its edge).
  virtual std::string scan_hint() const { return ""; }
  // Fills the norms of a fixed-parameter result from its x (one more product with A).
  void finish_fixed(DeconvolutionResult& r, const Eigen::VectorXd& b, double parameter) const {
    r.stats.residual_norm = robust_norm(b - a_->apply(r.x));
    r.stats.solution_norm = robust_norm(r.x);
    r.stats.chosen_parameter = parameter;
    r.cost.matvecs += 1;
  }

 private:
  // A nonzero x whose residual is not below ‖b‖ (to sqrt(eps), relative) fits the data no better than the trivial
  // answer x = 0 and is larger: not a regularized solution (e.g. the Landweber series on a zero eigenvalue grows
  // x linearly while the residual stays at ‖b‖; a truncation above the numerical rank divides by rounding noise).
  void no_better_than_zero(DeconvolutionResult& r, const Eigen::VectorXd& b) const {
    const double bn = robust_norm(b), res = r.stats.residual_norm;
    if (!(bn > 0) || !std::isfinite(res) || r.x.isZero(0)) return;
    const double tol = std::sqrt(std::numeric_limits<double>::epsilon());
    if (!(res >= (1.0 - tol) * bn)) return;
    char buf[256];
    std::snprintf(buf, sizeof buf, "residual ||b - A x|| = %.6g is not below ||b|| = %.6g (x = 0) while ||x|| = %.6g",
                  res, bn, r.stats.solution_norm);
    r.status = DeconvolutionStatus::numerical_issue;
    const std::string hint = no_fit_hint();
    r.stats.message = name_ + ": the solution fits the data no better than x = 0 (" + buf + ")" +
                      (hint.empty() ? "" : ": " + hint) + (r.stats.message.empty() ? "" : "; " + r.stats.message);
  }
  void require_setup() const {
    if (!a_) throw ConfigError("", name_ + ": solve() called before setup(A)");
  }
  static int max_entry_exponent(const ForwardOperator& a) {
    auto exponent = [](const Eigen::MatrixXd& m) {
      int e = 0;
      if (m.size() > 0) std::frexp(m.cwiseAbs().maxCoeff(), &e);
      return e;
    };
    switch (a.storage()) {
      case OperatorStorage::dense: return exponent(a.dense());
      case OperatorStorage::kronecker: return exponent(a.factor_x()) + exponent(a.factor_y());
      case OperatorStorage::sparse: {
        int e = 0;
        if (a.sparse().nonZeros() > 0)
          std::frexp(Eigen::Map<const Eigen::VectorXd>(a.sparse().valuePtr(), a.sparse().nonZeros()).cwiseAbs().maxCoeff(), &e);
        return e;
      }
    }
    return 0;
  }
  static Eigen::MatrixXd times_power_of_two(const Eigen::MatrixXd& m, int k) {
    return m.unaryExpr([k](double v) { return std::ldexp(v, k); });
  }
  static Eigen::VectorXd times_power_of_two(const Eigen::VectorXd& v, int k) {
    return v.unaryExpr([k](double e) { return std::ldexp(e, k); });
  }
  // Data b = 2^m b' with max|b'| in [1/2, 1) when b is badly scaled (|m| > 32; squares of 1e-200 underflow),
  // else m = 0 (b used as given). Every method is linear in b, so x scales with it.
  static int data_exponent(const Eigen::VectorXd& b) {
    if (b.size() == 0) return 0;
    const double top = b.cwiseAbs().maxCoeff();
    if (!(top > 0) || !std::isfinite(top)) return 0;
    int e = 0;
    std::frexp(top, &e);
    return std::abs(e) > 32 ? e : 0;
  }
  static ForwardOperator scaled_operator(const ForwardOperator& a, int k) {
    ForwardOperator s;
    switch (a.storage()) {
      case OperatorStorage::dense: s = ForwardOperator::from_dense(times_power_of_two(a.dense(), k)); break;
      case OperatorStorage::kronecker: {
        int ex = 0, ey = 0;
        if (a.factor_x().size() > 0) std::frexp(a.factor_x().cwiseAbs().maxCoeff(), &ex);
        ey = -k - ex;
        s = ForwardOperator::from_kronecker(times_power_of_two(a.factor_y(), -ey), times_power_of_two(a.factor_x(), -ex));
        break;
      }
      case OperatorStorage::sparse: {
        Eigen::SparseMatrix<double> m = a.sparse();
        for (Eigen::Index i = 0; i < m.nonZeros(); ++i) m.valuePtr()[i] = std::ldexp(m.valuePtr()[i], k);
        s = ForwardOperator::from_sparse(std::move(m));
        break;
      }
    }
    s.data_mesh = a.data_mesh, s.solution_mesh = a.solution_mesh, s.dimension = a.dimension;
    s.link_weights = a.link_weights;  // the priors of first_difference_zero_ends (scale-free: relative weights)
    s.difference_links = a.difference_links;
    return s;
  }
  // A fixed-parameter result of op() x' = 2^-m b back to A x = b: x = 2^(m-k) x', residual 2^m.
  void unscale(DeconvolutionResult& r, int m) const {
    if (scale_exponent_ == 0 && m == 0) return;
    const int xs = m - scale_exponent_;
    r.x = times_power_of_two(r.x, xs);
    r.stats.solution_norm = std::ldexp(r.stats.solution_norm, xs);
    r.stats.residual_norm = std::ldexp(r.stats.residual_norm, m);
    r.stats.chosen_parameter = unscale_parameter(r.stats.chosen_parameter);
    std::string note;
    if (scale_exponent_ != 0) note = "operator scaled by 2^" + std::to_string(-scale_exponent_);
    if (m != 0) note += (note.empty() ? "" : ", ") + std::string("data scaled by 2^") + std::to_string(-m);
    note += " for the solve";
    r.stats.message = r.stats.message.empty() ? note : r.stats.message + "; " + note;
  }

  std::string name_;
  RuleConfig rule_;
  std::string parameter_name_;
  const ForwardOperator* a_ = nullptr;
  std::optional<ForwardOperator> scaled_;  // set when the given operator is badly scaled
  int scale_exponent_ = 0;
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
