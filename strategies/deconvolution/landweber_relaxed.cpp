// Relaxed Landweber iteration x_{k+1} = x_k + ω Aᵀ(b − A x_k), x_0 = 0, for any (also rectangular) A.
// It converges for 0 < ω < 2/‖A‖₂²; the default ω = 1/‖A‖₂² is safe. The iteration count is the
// regularization parameter (stopped by the discrepancy principle or a fixed count).
#include <cmath>
#include <cstdio>

#include "strategies/deconvolution/deconvolver_base.hpp"
#include "strategies/deconvolution/deconvolvers.hpp"

namespace closurelab {
namespace {

class LandweberRelaxed : public DeconvolverBase {
 public:
  LandweberRelaxed(RuleConfig rule, double omega, int iterations, int max_iterations)
      : DeconvolverBase("landweber_relaxed", rule, "iterations"),
        omega_given_(omega), iterations_(iterations), max_iterations_(max_iterations) {}

 protected:
  void do_setup(const ForwardOperator& a) override {
    const double norm = a.norm2_estimate();
    norm_ = norm;
    if (!(norm > 0)) throw ConfigError("", "landweber_relaxed: the operator is zero");
    if (omega_given_ > 0) {
      const double omega = std::ldexp(omega_given_, 2 * scale_exponent());  // omega for op() = 2^-k A
      if (!(omega * norm * norm < 2.0))
        throw ConfigError("/omega", "omega = " + std::to_string(omega_given_) + " >= 2/||A||^2 = " +
                                        std::to_string(std::ldexp(2.0 / (norm * norm), 2 * scale_exponent())) +
                                        ": the iteration would diverge");
      omega_ = omega;
    } else {
      omega_ = 1.0 / (norm * norm);
    }
  }

  DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const override {
    DeconvolutionResult r;
    run(b, iterations_, [&](const ScanPoint& p) {
      if (!p.last && p.issue.empty()) return true;
      r = result_from_scan_point(p);
      return false;
    });
    // The best-determined mode (σ_1 = ‖A‖) keeps the fraction |1 − ω σ_1²|^k of its error after k iterations.
    // Over-relaxed (ω σ_1² > 1) that factor is negative: the mode oscillates about its value instead of settling,
    // and near ω = 2/σ_1² it has hardly moved (on A = I, ω = 1.9999999 returns x ~ 0 after 50 iterations). That is
    // not regularization (which damps the small singular values, not the largest): no_convergence.
    const double f = 1.0 - omega_ * norm_ * norm_;
    const double left = std::pow(std::abs(f), r.stats.iterations);
    if (r.status == DeconvolutionStatus::converged && f < 0 && r.stats.iterations > 0 && left > 0.5) {
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "landweber_relaxed: omega ||A||^2 = %.9g > 1 oscillates the largest singular mode, which keeps %.6g "
                    "of its error after %d iterations; use omega <= 1/||A||^2 (the default) or more iterations",
                    omega_ * norm_ * norm_, left, r.stats.iterations);
      r.status = DeconvolutionStatus::no_convergence;
      r.stats.message = buf;
    }
    return r;
  }

  void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const override { run(b, max_iterations_, visit); }
  std::string scan_hint() const override { return "the rules scan the iterations up to max_iterations"; }

 private:
  void run(const Eigen::VectorXd& b, int count, const ScanVisitor& visit) const {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(op().cols());
    Eigen::VectorXd r = b;
    double previous = robust_norm(b);
    const double floor = 1e-13 * robust_norm(b);
    for (int k = 0; k <= count; ++k) {
      if (k > 0) {
        x += omega_ * op().apply_transpose(r);
        r = b - op().apply(x);
      }
      ScanPoint p;
      p.parameter = k;
      p.residual_norm = robust_norm(r);
      p.solution_norm = robust_norm(x);
      p.matvecs = 2L * k;
      p.last = k == count;
      if (!(p.residual_norm <= (1.0 + 1e-10) * previous + floor)) {  // growth beyond rounding
        p.issue = "landweber_relaxed: the residual grows at iteration " + std::to_string(k) +
                  " (omega too large for this operator)";
        p.last = true;
      }
      p.solution = [&x] { return x; };
      if (!visit(p) || p.last) return;
      previous = p.residual_norm;
    }
  }
  double omega_given_, omega_ = 0.0, norm_ = 0.0;
  int iterations_, max_iterations_;
};

}  // namespace

ParamSchema landweber_relaxed_schema() {
  return {number_param("omega", 0.0, "relaxation omega; 0 = 1/||A||_2^2 (must be < 2/||A||_2^2)", 0.0),
          integer_param("iterations", 50, "iteration count (rule fixed)", 0, 10000000),
          integer_param("max_iterations", 5000, "largest count tried by the discrepancy/lcurve rules", 0, 10000000),
          rule_param({"fixed", "discrepancy", "lcurve"}, "fixed"), safety_param()};
}

std::unique_ptr<Deconvolver> make_landweber_relaxed(const json& p) {
  return std::make_unique<LandweberRelaxed>(RuleConfig::from_json(p), p.at("omega").get<double>(),
                                            p.at("iterations").get<int>(), p.at("max_iterations").get<int>());
}

}  // namespace closurelab
