// Tikhonov regularization (4.7) in two forms, with C = I or C = LᵀL for a first/second difference L:
//   paper          (A + α C) x = b                 (4.7) as written (square A);
//   least_squares  (AᵀA + α C) x = Aᵀ b            the normal equations of min ‖Ax − b‖² + α‖Lx‖².
// Backends: spectral (C = I: SVD, or the symmetric eigendecomposition for the paper form; Kronecker operators
// decompose their factors only), dense (Eigen Cholesky/LU per α) and sparse (CHOLMOD: symbolic analysis once,
// numeric factorization per α). Difference operators follow the solution mesh (1D, or the Kronecker sum
// [I ⊗ L_x; L_y ⊗ I] on a tensor mesh); they are not periodic.
#include <Eigen/CholmodSupport>
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <cstdio>
#include <limits>
#include <memory>
#include <unsupported/Eigen/KroneckerProduct>

#include "core/closure/spectral_basis.hpp"
#include "strategies/deconvolution/deconvolver_base.hpp"
#include "strategies/deconvolution/deconvolvers.hpp"
#include "strategies/deconvolution/difference_regularizers.hpp"

namespace closurelab {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// CHOLMOD's factorization with its reciprocal condition estimate (min/max of diag(L), squared for LL'):
// CHOLMOD only fails on a non-positive pivot, so a matrix that is singular to working precision (A'A + 1e-300 I
// for a 12x12 Hilbert A) factorizes "successfully" into garbage; the estimate says so.
class Cholmod : public Eigen::CholmodDecomposition<SpMat> {
 public:
  double rcond() { return m_cholmodFactor ? cholmod_rcond(m_cholmodFactor, &cholmod()) : 0.0; }
};

// A factorization whose reciprocal condition number is below the unit roundoff solves with no correct digit.
constexpr double singular_rcond = std::numeric_limits<double>::epsilon();

class Tikhonov : public DeconvolverBase {
 public:
  enum class Backend { automatic, spectral, dense, sparse };
  Tikhonov(RuleConfig rule, bool paper, int order, double alpha, Backend backend, double alpha_max, double alpha_min,
           int alpha_count)
      : DeconvolverBase("tikhonov", rule, "alpha"), paper_(paper), order_(order), alpha_(alpha), requested_(backend),
        alpha_max_(alpha_max), alpha_min_(alpha_min), alpha_count_(alpha_count) {}

 protected:
  void do_setup(const ForwardOperator& a) override {
    if (paper_ && !a.is_square())
      throw ConfigError("/form", "the paper form (A + alpha C) x = b needs a square A; got " + std::to_string(a.rows()) +
                                     "x" + std::to_string(a.cols()) + " (use form least_squares)");
    if (alpha_min_ >= alpha_max_) throw ConfigError("/alpha_min", "alpha_min must be below alpha_max");
    symmetric_ = a.is_symmetric(1e-10);
    backend_ = requested_;
    if (backend_ == Backend::automatic) {
      if (order_ == 0 && a.storage() != OperatorStorage::sparse && (!paper_ || symmetric_))
        backend_ = Backend::spectral;
      else
        backend_ = a.storage() == OperatorStorage::sparse ? Backend::sparse : Backend::dense;
    }
    if (backend_ == Backend::spectral && order_ != 0)
      throw ConfigError("/backend", "the spectral backend needs regularizer identity");
    if (backend_ != Backend::spectral && rule().rule == ParameterRule::gcv)
      throw ConfigError("/rule", "gcv needs the spectral backend (regularizer identity)");
    if (backend_ == Backend::spectral) {
      if (paper_ && !symmetric_)
        throw ConfigError("/backend", "the spectral paper form needs a symmetric A (use backend dense)");
      basis_ = SpectralBasis(a, paper_ ? SpectralBasis::Kind::symmetric_eigen : SpectralBasis::Kind::svd);
      const double smax = std::abs(basis_.sigma()(basis_.order()(0)));
      scale_ = paper_ ? smax : smax * smax;
      return;
    }
    const double norm = a.norm2_estimate();
    scale_ = paper_ ? norm : norm * norm;
    c_ = regularizer_matrix(a, order_);
    if (backend_ == Backend::dense) {
      const Eigen::MatrixXd ad = a.to_dense();
      g_dense_ = paper_ ? ad : Eigen::MatrixXd(ad.transpose() * ad);
      c_dense_ = Eigen::MatrixXd(c_);
    } else {
      const SpMat as = a.to_sparse();
      g_sparse_ = paper_ ? as : SpMat(as.transpose() * as);
      if (!paper_ || symmetric_) {
        cholmod_ = std::make_unique<Cholmod>();
        cholmod_->analyzePattern(SpMat(g_sparse_ + c_));
      }
    }
  }

  DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const override {
    DeconvolutionResult r;
    const double alpha = std::ldexp(alpha_, -(paper_ ? 1 : 2) * scale_exponent());  // alpha for op() = 2^-k A
    std::string issue;
    if (backend_ == Backend::spectral) {
      const Eigen::VectorXd beta = basis_.coefficients(b);
      r.x = spectral_solution(beta, alpha, issue);
      r.cost.matvecs = 2;
    } else {
      r.x = factored_solution(b, alpha, issue, true);
      r.cost.matvecs = paper_ ? 0 : 1;
    }
    // An alpha that dwarfs ||A||^2 (||A|| in the paper form) gives x ~ A'b/alpha ~ 0 and leaves the residual at
    // ||b||: a wrong scale, not a solution (alpha is absolute; the rules scan relative to ||A||^2).
    if (issue.empty() && !(alpha <= 1e12 * scale_))
      issue = "tikhonov: alpha = " + fmt(alpha_) + " is " + fmt(alpha / scale_) + " times " +
              (paper_ ? "||A||" : "||A||^2") + " (= " + fmt(std::ldexp(scale_, (paper_ ? 1 : 2) * scale_exponent())) +
              "): the regularization swamps the operator and x ~ 0; choose alpha on the scale of the operator or a rule";
    set_issue(r, issue);
    finish_fixed(r, b, alpha);
    return r;
  }
  double unscale_parameter(double alpha) const override {
    return std::ldexp(alpha, (paper_ ? 1 : 2) * scale_exponent());
  }
  static std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
  }

  void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const override {
    const auto grid = log_grid_descending(alpha_max_ * scale_, alpha_min_ * scale_, alpha_count_);
    const double m = static_cast<double>(op().rows());
    Eigen::VectorXd beta;
    double b_perp2 = 0.0;
    if (backend_ == Backend::spectral) {
      beta = basis_.coefficients(b);
      // b_⊥ (the part of b outside range(U)) is nonzero only when A has more rows than singular values.
      if (basis_.data_size() > beta.size()) b_perp2 = std::max(b.squaredNorm() - beta.squaredNorm(), 0.0);
    }
    long matvecs = backend_ == Backend::spectral ? 1 : 0;
    for (size_t g = 0; g < grid.size(); ++g) {
      const double alpha = grid[g];
      ScanPoint p;
      p.parameter = alpha;
      p.last = g + 1 == grid.size();
      Eigen::VectorXd x;
      if (backend_ == Backend::spectral) {
        // Filter factors f_i = σ_i φ_i; residual Σ((1 − f_i) β_i)² + ‖b_⊥‖²; GCV ‖r‖²/(m − Σ f_i)².
        double r2 = b_perp2, x2 = 0.0, trace = 0.0;
        for (Eigen::Index i = 0; i < beta.size(); ++i) {
          const double s = basis_.sigma()(i), phi = filter(s, alpha);
          r2 += (1.0 - s * phi) * (1.0 - s * phi) * beta(i) * beta(i);
          x2 += phi * phi * beta(i) * beta(i);
          trace += s * phi;
        }
        p.residual_norm = std::sqrt(r2);
        p.solution_norm = std::sqrt(x2);
        p.gcv = r2 / ((m - trace) * (m - trace));
        if (paper_ && basis_.sigma().minCoeff() + alpha <= 1e-14 * scale_)
          p.issue = indefinite_message(alpha);
        p.matvecs = matvecs + 1;
        p.solution = [this, &beta, alpha] {
          std::string ignored;
          return spectral_solution(beta, alpha, ignored);
        };
      } else {
        x = factored_solution(b, alpha, p.issue);
        matvecs += (paper_ ? 0 : 1) + 1;
        p.residual_norm = robust_norm(b - op().apply(x));
        p.solution_norm = robust_norm(x);
        p.matvecs = matvecs;
        p.solution = [&x] { return x; };
      }
      if (!p.issue.empty()) p.last = true;
      if (!visit(p) || p.last) return;
    }
  }

 private:
  // x-coefficient φ(σ); singular values below the numerical rank tolerance are treated as zero.
  double filter(double s, double alpha) const {
    if (std::abs(s) <= basis_.rank_tolerance()) return 0.0;
    return paper_ ? 1.0 / (s + alpha) : s / (s * s + alpha);
  }
  std::string indefinite_message(double alpha) const {
    return "tikhonov: A + alpha C is not positive definite (alpha = " + std::to_string(alpha) +
           ", smallest eigenvalue of A " + std::to_string(basis_.sigma().minCoeff()) + "); use form least_squares";
  }
  static void set_issue(DeconvolutionResult& r, const std::string& issue) {
    if (issue.empty()) return;
    r.status = DeconvolutionStatus::numerical_issue;
    r.stats.message = issue;
  }
  Eigen::VectorXd spectral_solution(const Eigen::VectorXd& beta, double alpha, std::string& issue) const {
    if (paper_ && basis_.sigma().minCoeff() + alpha <= 1e-14 * scale_) issue = indefinite_message(alpha);
    Eigen::VectorXd c(beta.size());
    for (Eigen::Index i = 0; i < beta.size(); ++i) c(i) = filter(basis_.sigma()(i), alpha) * beta(i);
    return basis_.synthesize(c);
  }
  // `check_conditioning` (the fixed-parameter solve): a Cholesky factor whose reciprocal condition estimate is
  // below the unit roundoff is reported as not positive definite to working precision (the scan's smallest
  // alphas are bounded by alpha_min and keep their behaviour).
  Eigen::VectorXd factored_solution(const Eigen::VectorXd& b, double alpha, std::string& issue,
                                    bool check_conditioning = false) const {
    const Eigen::VectorXd rhs = paper_ ? b : op().apply_transpose(b);
    const std::string not_pd = "tikhonov: the matrix " + std::string(paper_ ? "A + alpha C" : "A'A + alpha C") +
                               " is not positive definite at alpha = " + fmt(alpha);
    auto singular = [&](double rc, const char* how) {
      issue = not_pd + " to working precision: reciprocal condition estimate " + fmt(rc) + " (" + how +
              ") is below the unit roundoff; increase alpha" + (paper_ ? "" : " (the normal equations square the condition number)");
    };
    if (backend_ == Backend::dense) {
      const Eigen::MatrixXd k = g_dense_ + alpha * c_dense_;
      if (paper_ && !symmetric_) return k.partialPivLu().solve(rhs);
      Eigen::LLT<Eigen::MatrixXd> llt(k);
      if (llt.info() != Eigen::Success) {
        issue = not_pd;
        return Eigen::VectorXd::Zero(op().cols());
      }
      if (check_conditioning) {
        const double rc = llt.rcond();
        if (!(rc >= singular_rcond)) singular(rc, "Eigen LLT");
      }
      return llt.solve(rhs);
    }
    const SpMat k = g_sparse_ + alpha * c_;
    if (paper_ && !symmetric_) {
      Eigen::SparseLU<SpMat> lu(k);
      if (lu.info() != Eigen::Success) {
        issue = "tikhonov: sparse LU of A + alpha C failed at alpha = " + std::to_string(alpha);
        return Eigen::VectorXd::Zero(op().cols());
      }
      return lu.solve(rhs);
    }
    cholmod_->factorize(k);
    if (cholmod_->info() != Eigen::Success) {
      issue = not_pd + " (CHOLMOD)";
      return Eigen::VectorXd::Zero(op().cols());
    }
    if (check_conditioning) {
      const double rc = cholmod_->rcond();
      if (!(rc >= singular_rcond)) singular(rc, "CHOLMOD, (min/max diag L)^2");
    }
    return cholmod_->solve(rhs);
  }

  bool paper_;
  int order_;
  double alpha_;
  Backend requested_, backend_ = Backend::spectral;
  double alpha_max_, alpha_min_;
  int alpha_count_;
  bool symmetric_ = false;
  double scale_ = 1.0;
  SpectralBasis basis_;
  SpMat c_, g_sparse_;
  Eigen::MatrixXd g_dense_, c_dense_;
  std::unique_ptr<Cholmod> cholmod_;  // factorize() mutates; see note in solve
};

}  // namespace

ParamSchema tikhonov_schema() {
  return {string_param("form", "least_squares", "paper: (A + alpha C)x = b (4.7); least_squares: (A'A + alpha C)x = A'b",
                       {"paper", "least_squares"}),
          string_param("regularizer", "identity",
                       "C = I, or C = L'L for a first/second difference L; first_difference_zero_ends: L includes the "
                       "links to known zeros beyond both ends, weighted by the operator's link weights (a channel's "
                       "viscosity: the minimum-viscous-dissipation prior)",
                       {"identity", "first_difference", "second_difference", "first_difference_zero_ends"}),
          number_param("alpha", 1e-6, "regularization parameter alpha (rule fixed)", 0.0, {}, true),
          string_param("backend", "auto", "auto, spectral (C = I; SVD/eigen, Kronecker-aware), dense (Eigen), sparse (CHOLMOD)",
                       {"auto", "spectral", "dense", "sparse"}),
          number_param("alpha_max", 1.0, "largest alpha scanned by the rules, relative to ||A||^2 (||A|| paper form)", 0.0, {}, true),
          number_param("alpha_min", 1e-16, "smallest alpha scanned by the rules, relative likewise", 0.0, {}, true),
          integer_param("alpha_count", 61, "number of alphas in the rules' geometric scan", 3, 100000),
          rule_param({"fixed", "discrepancy", "gcv", "lcurve"}, "fixed"), safety_param()};
}

std::unique_ptr<Deconvolver> make_tikhonov(const json& p) {
  if (!(p.at("alpha_min").get<double>() < p.at("alpha_max").get<double>()))
    throw ConfigError("/alpha_min", "alpha_min = " + p.at("alpha_min").dump() + " must be below alpha_max = " +
                                        p.at("alpha_max").dump());
  const std::string reg = p.at("regularizer").get<std::string>();
  const std::string be = p.at("backend").get<std::string>();
  const auto backend = be == "spectral" ? Tikhonov::Backend::spectral
                       : be == "dense"  ? Tikhonov::Backend::dense
                       : be == "sparse" ? Tikhonov::Backend::sparse
                                        : Tikhonov::Backend::automatic;
  return std::make_unique<Tikhonov>(RuleConfig::from_json(p), p.at("form").get<std::string>() == "paper",
                                    reg == "identity"           ? 0
                                    : reg == "first_difference" ? 1
                                    : reg == "second_difference" ? 2
                                                                 : 3,
                                    p.at("alpha").get<double>(), backend, p.at("alpha_max").get<double>(),
                                    p.at("alpha_min").get<double>(), p.at("alpha_count").get<int>());
}

}  // namespace closurelab
