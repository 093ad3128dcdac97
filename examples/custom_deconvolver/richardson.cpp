// The Richardson iteration x_{k+1} = x_k + omega (b - A x_k), x_0 = 0, on a square A (for the symmetric positive
// definite averaging operators it converges when 0 < omega < 2/||A||_2; the default omega = 1/||A||_2 is safe).
// The iteration count is the regularization parameter, fixed or chosen by the discrepancy principle. With
// omega = 1 it is the paper's Landweber series (4.3): x_n = sum_{k<n} (I - A)^k b.
//
// It derives from closurelab's DeconvolverBase (installed: strategies/deconvolution/deconvolver_base.hpp),
// which handles the parameter rule, the input checks, timing and the NaN guard; a strategy writes setup, a
// fixed-parameter solve and the scan of its regularized family.
#include "richardson.hpp"

#include <string>

#include "strategies/deconvolution/deconvolver_base.hpp"

namespace closurelab_example {
namespace {

using namespace closurelab;

class Richardson : public DeconvolverBase {
 public:
  Richardson(RuleConfig rule, double omega, int iterations, int max_iterations)
      : DeconvolverBase("richardson", rule, "iterations"),
        omega_given_(omega), iterations_(iterations), max_iterations_(max_iterations) {}

 protected:
  void do_setup(const ForwardOperator& a) override {
    if (a.rows() != a.cols())
      throw ConfigError("", "richardson needs a square operator, got " + std::to_string(a.rows()) + " x " +
                                std::to_string(a.cols()) + " (use the coarse_coarse or fine_fine discretization)");
    const double norm = a.norm2_estimate();
    if (!(norm > 0)) throw ConfigError("", "richardson: the operator is zero");
    if (omega_given_ * norm >= 2.0)
      throw ConfigError("/omega", "omega = " + std::to_string(omega_given_) + " >= 2/||A||_2 = " +
                                      std::to_string(2.0 / norm) + ": the iteration would diverge");
    omega_ = omega_given_ > 0 ? omega_given_ : 1.0 / norm;
  }

  DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const override {
    DeconvolutionResult r;
    run(b, iterations_, [&](const ScanPoint& p) {
      if (!p.last && p.issue.empty()) return true;
      r = result_from_scan_point(p);
      return false;
    });
    return r;
  }

  void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const override { run(b, max_iterations_, visit); }

 private:
  // Visits x_0 = 0, x_1, ..., x_count; stops early (with an issue) when the residual grows, which happens when
  // A has eigenvalues outside (0, 2/omega), e.g. a truncated Gaussian's negative ones.
  void run(const Eigen::VectorXd& b, int count, const ScanVisitor& visit) const {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(op().cols());
    Eigen::VectorXd r = b;
    double previous = b.norm();
    const double floor = 1e-13 * b.norm();
    for (int k = 0; k <= count; ++k) {
      if (k > 0) {
        x += omega_ * r;
        r = b - op().apply(x);
      }
      ScanPoint p;
      p.parameter = k;
      p.residual_norm = r.norm();
      p.solution_norm = x.norm();
      p.matvecs = k;
      p.last = k == count;
      if (!(p.residual_norm <= (1.0 + 1e-10) * previous + floor)) {
        p.issue = "richardson: the residual grows at iteration " + std::to_string(k) +
                  " (omega too large, or A not positive definite)";
        p.last = true;
      }
      p.solution = [&x] { return x; };
      if (!visit(p) || p.last) return;
      previous = p.residual_norm;
    }
  }

  double omega_given_, omega_ = 0.0;
  int iterations_, max_iterations_;
};

ParamSchema richardson_schema() {
  return {number_param("omega", 0.0, "step size omega; 0 = 1/||A||_2 (must be < 2/||A||_2)", 0.0),
          integer_param("iterations", 10, "iteration count (rule fixed)", 0, 10000000),
          integer_param("max_iterations", 5000, "largest count tried by the discrepancy rule", 0, 10000000),
          rule_param({"fixed", "discrepancy"}, "fixed"), safety_param()};
}

std::unique_ptr<Deconvolver> make_richardson(const json& p) {
  return std::make_unique<Richardson>(RuleConfig::from_json(p), p.at("omega").get<double>(),
                                      p.at("iterations").get<int>(), p.at("max_iterations").get<int>());
}

}  // namespace

void register_richardson(Registry& registry) {
  registry.deconvolvers.add({"richardson", "Richardson iteration x_{k+1} = x_k + omega (b - A x_k), square A (example)",
                             richardson_schema()},
                            make_richardson);
}

}  // namespace closurelab_example
