// Krylov deconvolvers (§4.2 "the conjugate gradient method"), regularized by early stopping:
//   cg    CG on A x = b for a symmetric positive definite A. A sampled truncated Gaussian can have negative
//         eigenvalues (DESIGN.md §6); CG refuses such an A with status numerical_issue — at setup when the
//         spectrum is cheap to check (Kronecker factors, or dense up to 2000 unknowns), otherwise when a
//         direction of non-positive curvature pᵀAp <= 0 shows up.
//   cgls  CG on the normal equations AᵀA x = Aᵀb without forming AᵀA (any A, also rectangular).
#include <Eigen/Eigenvalues>

#include "strategies/deconvolution/deconvolver_base.hpp"
#include "strategies/deconvolution/deconvolvers.hpp"

namespace closurelab {
namespace {

ScanPoint point(double k, const Eigen::VectorXd& x, double rnorm, long matvecs, bool last) {
  ScanPoint p;
  p.parameter = k;
  p.residual_norm = rnorm;
  p.solution_norm = robust_norm(x);
  p.matvecs = matvecs;
  p.last = last;
  p.solution = [&x] { return x; };
  return p;
}

class KrylovBase : public DeconvolverBase {
 public:
  KrylovBase(std::string name, RuleConfig rule, int iterations, int max_iterations, double tolerance)
      : DeconvolverBase(std::move(name), rule, "iterations"),
        iterations_(iterations), max_iterations_(max_iterations), tolerance_(tolerance) {}

 protected:
  DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const override {
    DeconvolutionResult r;
    run(b, iterations_, tolerance_, [&](const ScanPoint& p) {
      if (!p.last && p.issue.empty()) return true;
      r = result_from_scan_point(p);
      return false;
    });
    return r;
  }
  void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const override {
    run(b, max_iterations_, -1.0, visit);  // tolerance < 0: a scan
  }
  std::string scan_hint() const override {
    return "the rules scan the iterations up to max_iterations, or until the residual has not improved for patience "
           "iterations";
  }
  // Scans only: CG's residual is not monotone; once it has not improved on its minimum for `patience`
  // iterations the semi-convergence is over and the scan ends (the rules then fall back to that minimum).
  bool stalled(double rnorm, double& min_rnorm, int& since) const {
    if (rnorm < min_rnorm) {
      min_rnorm = rnorm;
      since = 0;
      return false;
    }
    return ++since >= patience_;
  }
  int patience_ = 10;
  virtual void run(const Eigen::VectorXd& b, int count, double tolerance, const ScanVisitor& visit) const = 0;

  int iterations_, max_iterations_;
  double tolerance_;
};

class ConjugateGradient : public KrylovBase {
 public:
  ConjugateGradient(RuleConfig rule, int iterations, int max_iterations, double tolerance, bool spd_check, int patience)
      : KrylovBase("cg", rule, iterations, max_iterations, tolerance), spd_check_(spd_check) {
    patience_ = patience;
  }

 protected:
  void do_setup(const ForwardOperator& a) override {
    refusal_.clear();
    if (!a.is_square()) {
      refusal_ = "cg refused: A is " + std::to_string(a.rows()) + "x" + std::to_string(a.cols()) +
                 ", not square (use cgls)";
      return;
    }
    if (!a.is_symmetric(1e-10)) {
      refusal_ = "cg refused: A is not symmetric (use cgls)";
      return;
    }
    if (!spd_check_) return;
    auto min_eig = [](const Eigen::MatrixXd& m, double& lo, double& hi) {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e(0.5 * (m + m.transpose()), Eigen::EigenvaluesOnly);
      lo = e.eigenvalues().minCoeff();
      hi = e.eigenvalues().maxCoeff();
    };
    double lambda_min = 0.0, lambda_max = 0.0;
    if (a.storage() == OperatorStorage::kronecker) {
      double lx, hx, ly, hy;
      min_eig(a.factor_x(), lx, hx);
      min_eig(a.factor_y(), ly, hy);
      lambda_min = std::min({lx * ly, lx * hy, hx * ly, hx * hy});
      lambda_max = std::max({lx * ly, lx * hy, hx * ly, hx * hy});
    } else if (a.cols() <= 2000) {
      min_eig(a.to_dense(), lambda_min, lambda_max);
    } else {
      return;  // the curvature test in the iteration is the guard
    }
    // Eigenvalues at rounding level (|λ| <= 1e-12 λ_max) count as semidefinite; the curvature test guards those.
    if (lambda_min < -1e-12 * std::abs(lambda_max))
      refusal_ = "cg refused: A is not positive definite (smallest eigenvalue " + std::to_string(lambda_min) +
                 ", largest " + std::to_string(lambda_max) + "); use cgls, tikhonov or tsvd";
  }

  void run(const Eigen::VectorXd& b, int count, double tolerance, const ScanVisitor& visit) const override {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(op().cols());
    if (!refusal_.empty()) {
      ScanPoint p = point(0, x, robust_norm(b), 0, true);
      p.issue = refusal_;
      visit(p);
      return;
    }
    Eigen::VectorXd r = b, p = r;
    double rs = r.squaredNorm();
    const double stop = std::max(tolerance, 0.0) * robust_norm(b);
    const bool scanning = tolerance < 0.0;
    double min_rnorm = std::sqrt(rs);
    int since = 0;
    long matvecs = 0;
    if (!visit(point(0, x, std::sqrt(rs), matvecs, count == 0 || rs == 0.0))) return;
    if (count == 0 || rs == 0.0) return;
    for (int k = 1; k <= count; ++k) {
      const Eigen::VectorXd q = op().apply(p);
      ++matvecs;
      const double curvature = p.dot(q);
      if (!(curvature > 0.0)) {
        ScanPoint pt = point(k - 1, x, std::sqrt(rs), matvecs, true);
        pt.issue = "cg: non-positive curvature p'Ap = " + std::to_string(curvature) + " at iteration " +
                   std::to_string(k) + ": A is not positive definite (use cgls)";
        visit(pt);
        return;
      }
      const double alpha = rs / curvature;
      x += alpha * p;
      r -= alpha * q;
      const double rs_new = r.squaredNorm();
      const bool last = k == count || rs_new == 0.0 || std::sqrt(rs_new) <= stop ||
                        (scanning && stalled(std::sqrt(rs_new), min_rnorm, since));
      if (!visit(point(k, x, std::sqrt(rs_new), matvecs, last)) || last) return;
      p = r + (rs_new / rs) * p;
      rs = rs_new;
    }
  }

 private:
  bool spd_check_;
  std::string refusal_;
};

class Cgls : public KrylovBase {
 public:
  Cgls(RuleConfig rule, int iterations, int max_iterations, double tolerance)
      : KrylovBase("cgls", rule, iterations, max_iterations, tolerance) {}

 protected:
  void do_setup(const ForwardOperator&) override {}

  void run(const Eigen::VectorXd& b, int count, double tolerance, const ScanVisitor& visit) const override {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(op().cols());
    Eigen::VectorXd r = b;
    Eigen::VectorXd s = op().apply_transpose(r);
    long matvecs = 1;
    Eigen::VectorXd p = s;
    double gamma = s.squaredNorm();
    const double gamma0 = gamma;
    if (!visit(point(0, x, robust_norm(r), matvecs, count == 0 || gamma == 0.0))) return;
    if (count == 0 || gamma == 0.0) return;
    for (int k = 1; k <= count; ++k) {
      const Eigen::VectorXd q = op().apply(p);
      const double qq = q.squaredNorm();
      if (!(qq > 0.0) || !std::isfinite(qq)) {  // ||Ap||^2 under- or overflowed: stop with x so far, as an issue
        ScanPoint pt = point(k - 1, x, robust_norm(r), matvecs, true);
        pt.issue = "cgls: ||A p||^2 = " + std::to_string(qq) + " at iteration " + std::to_string(k) +
                   " (under- or overflow; the operator or data are badly scaled)";
        visit(pt);
        return;
      }
      const double alpha = gamma / qq;
      x += alpha * p;
      r -= alpha * q;
      s = op().apply_transpose(r);
      matvecs += 2;
      const double gamma_new = s.squaredNorm();
      // Stop when the normal-equation residual ‖Aᵀr‖ is negligible (the least-squares solution is reached).
      const bool last = k == count || gamma_new == 0.0 || std::sqrt(gamma_new) <= std::max(tolerance, 1e-15) * std::sqrt(gamma0);
      if (!visit(point(k, x, robust_norm(r), matvecs, last)) || last) return;
      p = s + (gamma_new / gamma) * p;
      gamma = gamma_new;
    }
  }
};

ParamSchema krylov_schema(int default_iterations) {
  return {integer_param("iterations", default_iterations, "iteration count (rule fixed)", 0, 10000000),
          integer_param("max_iterations", 500, "largest count tried by the discrepancy/lcurve rules", 0, 10000000),
          number_param("tolerance", 1e-14, "stop a fixed-count run early when the relative residual falls below", 0.0, 1.0),
          rule_param({"fixed", "discrepancy", "lcurve"}, "fixed"), safety_param()};
}

}  // namespace

ParamSchema cg_schema() {
  ParamSchema s = krylov_schema(50);
  s.push_back(bool_param("spd_check", true, "check positive definiteness from the spectrum at setup where affordable"));
  s.push_back(integer_param("patience", 3, "rules: end the scan when the residual has not improved for this many iterations", 1, 1000000));
  return s;
}
std::unique_ptr<Deconvolver> make_cg(const json& p) {
  return std::make_unique<ConjugateGradient>(RuleConfig::from_json(p), p.at("iterations").get<int>(),
                                             p.at("max_iterations").get<int>(), p.at("tolerance").get<double>(),
                                             p.at("spd_check").get<bool>(), p.at("patience").get<int>());
}
ParamSchema cgls_schema() { return krylov_schema(50); }
std::unique_ptr<Deconvolver> make_cgls(const json& p) {
  return std::make_unique<Cgls>(RuleConfig::from_json(p), p.at("iterations").get<int>(),
                                p.at("max_iterations").get<int>(), p.at("tolerance").get<double>());
}

}  // namespace closurelab
