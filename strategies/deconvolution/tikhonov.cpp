// Tikhonov regularization (4.7) in two forms, with C = I or C = LᵀL for a first/second difference L:
//   paper          (A + α C) x = b                 (4.7) as written (square A);
//   least_squares  min ‖Ax − b‖² + α‖Lx‖²          (whose normal equations are (AᵀA + α C) x = Aᵀ b; never formed).
// Backends:
//   spectral  filter factors for every α from one decomposition: C = I by the SVD (or, for the paper form, the
//             symmetric eigendecomposition; Kronecker operators decompose their factors only); a difference L
//             (least_squares) by the transformation to standard form and one SVD (standard_form.hpp: the
//             generalized SVD's filter factors). The paper form with a difference C has no filter-factor form.
//   dense     least_squares: Eigen's column-pivoting Householder QR of the stacked [A; √α L] per α; paper: Eigen
//             Cholesky/LU of A + α C per α.
//   sparse    least_squares: Eigen's SparseQR (COLAMD) of the stacked [A; √α L] per α; paper: CHOLMOD (symbolic
//             analysis once) or SparseLU of A + α C.
//   dual      least_squares with a fixed α: C = I, x = Aᵀ (AAᵀ + αI)⁻¹ b, Eigen's Cholesky of the m × m matrix
//             (m the data size) once at setup: for a wide A (m ≪ n: the 2D force-density model's coarse data on a
//             finer reconstruction) a setup of O(m² n) instead of the SVD's, whose condition is 1 + ‖A‖²/α (the
//             square of the stacked system's): refused as a numerical issue where its reciprocal estimate falls
//             below 1e-11 (x then carries relative errors up to ~1e-5); a first difference L (each row one link),
//             x = G Aᵀ y + N z from the m × m system A G Aᵀ + αI bordered by L's null space N, G the grounded
//             (LᵀL)⁻¹ by CHOLMOD (DualDifferenceSystem): O(m n) memory instead of the standard form's n²; rules need
//             the spectral backend.
//   auto      spectral for a dense or Kronecker A in the least-squares form (and for the paper form with C = I on a
//             symmetric A), else dense or sparse as A is stored.
// The least-squares solves never square the condition number of A (DESIGN.md §6); with rule fixed the stacked QR is
// computed once, at setup (the paper form factors per solve, as before). GCV needs the trace of the influence
// matrix: Σ f_i (+ dim null(L)) from the filter factors, or ‖R⁻ᵀ Pᵀ Aᵀ‖²_F from the stacked QR ([A; √α L] P = Q R,
// so A P = Q_top R), or trace((A + αC)⁻¹ A) from the paper form's factorization.
// Difference operators follow the solution mesh (1D, or the Kronecker sum [I ⊗ L_x; L_y ⊗ I] on a tensor mesh);
// they are not periodic.
// One file above the project's 320-line guide: the two forms and four backends share one scan, one GCV and one
// parameter schema (one class); the standard-form transformation, an idea of its own, is standard_form.cpp, the
// factorisations tikhonov_factorizations.hpp.
#include <Eigen/CholmodSupport>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SparseLU>
#include <Eigen/SparseQR>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>
#include <unsupported/Eigen/KroneckerProduct>

#include "core/closure/spectral_basis.hpp"
#include "strategies/deconvolution/deconvolver_base.hpp"
#include "strategies/deconvolution/deconvolvers.hpp"
#include "strategies/deconvolution/difference_regularizers.hpp"
#include "strategies/deconvolution/standard_form.hpp"
#include "strategies/deconvolution/tikhonov_factorizations.hpp"

namespace closurelab {
namespace {

using namespace tikhonov_detail;

class Tikhonov : public DeconvolverBase {
 public:
  enum class Backend { automatic, spectral, dense, sparse, dual };
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
    fixed_qr_.reset();
    std_form_.reset();
    dual_.reset();
    dual_difference_.reset();
    if (backend_ == Backend::dual) return setup_dual(a);
    if (backend_ == Backend::automatic) {
      if (a.storage() != OperatorStorage::sparse && (paper_ ? order_ == 0 && symmetric_ : true))
        backend_ = Backend::spectral;
      else
        backend_ = a.storage() == OperatorStorage::sparse ? Backend::sparse : Backend::dense;
    }
    if (backend_ == Backend::spectral && paper_ && order_ != 0)
      throw ConfigError("/backend", "the spectral backend's paper form needs regularizer identity ((A + alpha L'L) x = b "
                                    "has no filter-factor form); use backend dense or sparse, or form least_squares");
    if (backend_ == Backend::spectral && order_ == 0) {
      if (paper_ && !symmetric_)
        throw ConfigError("/backend", "the spectral paper form needs a symmetric A (use backend dense)");
      basis_ = SpectralBasis(a, paper_ ? SpectralBasis::Kind::symmetric_eigen : SpectralBasis::Kind::svd);
      const double smax = std::abs(basis_.sigma()(basis_.order()(0)));
      scale_ = paper_ ? smax : smax * smax;
      return;
    }
    const double norm = a.norm2_estimate();
    scale_ = paper_ ? norm : norm * norm;
    l_ = regularizer_operator(a, order_);
    if (backend_ == Backend::spectral) {  // least_squares with a difference L: the standard form
      std_form_ = std::make_unique<StandardForm>(a, l_);
      return;
    }
    if (!paper_) {
      if (backend_ == Backend::dense) {
        a_dense_ = a.to_dense();
        l_dense_ = Eigen::MatrixXd(l_);
      } else {
        a_sparse_ = a.to_sparse();
      }
      if (rule().rule == ParameterRule::fixed) fixed_qr_ = stacked_qr(fixed_alpha());
      return;
    }
    c_ = regularizer_matrix(a, order_);
    if (backend_ == Backend::dense) {
      g_dense_ = a.to_dense();
      c_dense_ = Eigen::MatrixXd(c_);
    } else {
      g_sparse_ = a.to_sparse();
      if (symmetric_) {
        cholmod_ = std::make_unique<Cholmod>();
        cholmod_->analyzePattern(SpMat(g_sparse_ + c_));
      }
    }
  }

  DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const override {
    DeconvolutionResult r;
    const double alpha = fixed_alpha();
    std::string issue;
    if (backend_ == Backend::dual) {
      r.x = dual_solution(b, issue).col(0);
      r.cost.matvecs = 1;
    } else if (backend_ == Backend::spectral) {
      if (std_form_) {
        r.x = std_form_->solution(std_form_->data(b), alpha);
      } else {
        const Eigen::VectorXd beta = basis_.coefficients(b);
        r.x = spectral_solution(beta, alpha, issue);
      }
      r.cost.matvecs = 2;
    } else {
      r.x = factored_solution(b, alpha, issue, true);
      r.cost.matvecs = paper_ ? 0 : 1;
    }
    if (issue.empty()) issue = swamped(alpha);
    set_issue(r, issue);
    finish_fixed(r, b, alpha);
    return r;
  }
  // Many right-hand sides by matrix products: the SVD's filter factors (C = I) or the dual system's factor.
  FixedColumns solve_fixed_columns(const Eigen::MatrixXd& b) const override {
    FixedColumns out;
    const double alpha = fixed_alpha();
    out.parameter = alpha;
    if (backend_ == Backend::dual) {
      out.x = dual_solution(b, out.issue);
      out.matvecs_per_column = 1;
    } else if (backend_ == Backend::spectral && !std_form_) {
      Eigen::MatrixXd c = basis_.coefficients(b);
      Eigen::VectorXd phi(c.rows());
      for (Eigen::Index i = 0; i < phi.size(); ++i) phi(i) = filter(basis_.sigma()(i), alpha);
      c = phi.asDiagonal() * c;
      out.x = basis_.synthesize(c);
      out.matvecs_per_column = 2;
      if (paper_ && basis_.sigma().minCoeff() + alpha <= 1e-14 * scale_) out.issue = indefinite_message(alpha);
    } else {
      return {};
    }
    if (out.issue.empty()) out.issue = swamped(alpha);
    return out;
  }
  // An alpha that dwarfs ||A||^2 (||A|| in the paper form) gives x ~ A'b/alpha ~ 0 and leaves the residual at
  // ||b||: a wrong scale, not a solution (alpha is absolute; the rules scan relative to ||A||^2).
  std::string swamped(double alpha) const {
    if (alpha <= 1e12 * scale_) return "";
    return "tikhonov: alpha = " + fmt(alpha_) + " is " + fmt(alpha / scale_) + " times " +
           (paper_ ? "||A||" : "||A||^2") + " (= " + fmt(std::ldexp(scale_, (paper_ ? 1 : 2) * scale_exponent())) +
           "): the regularization swamps the operator and x ~ 0; choose alpha on the scale of the operator or a rule";
  }
  // Hansen's L-curve of general-form Tikhonov plots ‖Lx‖, the penalized seminorm.
  Seminorm lcurve_seminorm() const override {
    if (order_ == 0) return {};
    return [this](const Eigen::VectorXd& x) { return robust_norm(l_ * x); };
  }
  std::string scan_hint() const override {
    return "the rules scan alpha from alpha_min to alpha_max, relative to ||A||^2: lower alpha_min or raise alpha_max";
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
    if (backend_ == Backend::dual)  // setup_dual refuses a rule; a direct scan of a fixed-alpha instance has none
      throw ConfigError("/backend", "tikhonov: backend dual serves a fixed alpha and has no scan; use backend spectral");
    const auto grid = log_grid_descending(alpha_max_ * scale_, alpha_min_ * scale_, alpha_count_);
    const double m = static_cast<double>(op().rows());
    const bool want_gcv = rule().rule == ParameterRule::gcv;
    Eigen::VectorXd beta;
    double b_perp2 = 0.0;
    StandardForm::Data sf;
    if (std_form_) {
      sf = std_form_->data(b);
    } else if (backend_ == Backend::spectral) {
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
      if (std_form_) {
        // The generalized SVD's filter factors f_i = σ̄_i φ_i; residual Σ((1 − f_i) β̄_i)² + ‖b̄_⊥‖²; GCV
        // ‖r‖²/(m − dim null(L) − Σ f_i)².
        double r2 = sf.outside2, trace = static_cast<double>(std_form_->null_dimension());
        for (Eigen::Index i = 0; i < sf.beta.size(); ++i) {
          const double f = std_form_->sigma()(i) * std_form_->filter(i, alpha);
          r2 += (1.0 - f) * (1.0 - f) * sf.beta(i) * sf.beta(i);
          trace += f;
        }
        x = std_form_->solution(sf, alpha);
        p.residual_norm = std::sqrt(r2);
        p.solution_norm = robust_norm(x);
        p.gcv = r2 / ((m - trace) * (m - trace));
        p.matvecs = matvecs + 1;
        p.solution = [&x] { return x; };
      } else if (backend_ == Backend::spectral) {
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
        double trace = -1.0;
        x = factored_solution(b, alpha, p.issue, false, want_gcv ? &trace : nullptr);
        matvecs += (paper_ ? 0 : 1) + 1;
        const Eigen::VectorXd residual = b - op().apply(x);
        p.residual_norm = robust_norm(residual);
        p.solution_norm = robust_norm(x);
        if (trace >= 0) p.gcv = residual.squaredNorm() / ((m - trace) * (m - trace));
        p.matvecs = matvecs;
        p.solution = [&x] { return x; };
      }
      if (!p.issue.empty()) p.last = true;
      if (!visit(p) || p.last) return;
    }
  }

 private:
  double fixed_alpha() const { return std::ldexp(alpha_, -(paper_ ? 1 : 2) * scale_exponent()); }  // for op() = 2^-k A
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
  void setup_dual(const ForwardOperator& a) {
    if (paper_) throw ConfigError("/backend", "backend dual serves the least_squares form");
    if (order_ == 2)
      throw ConfigError("/backend", "backend dual serves regularizer identity or a first difference; use backend spectral");
    if (rule().rule != ParameterRule::fixed)
      throw ConfigError("/backend", "backend dual serves a fixed alpha (rule fixed); the rules need backend spectral");
    if (a.storage() != OperatorStorage::dense) a_dense_ = a.to_dense();
    dual_a_ = a.storage() == OperatorStorage::dense ? &a.dense() : &a_dense_;  // a outlives the instance
    if (order_ != 0) {
      const double norm = a.norm2_estimate();
      scale_ = norm * norm;
      dual_difference_ = std::make_unique<DualDifferenceSystem>(*dual_a_, regularizer_operator(a, order_), fixed_alpha());
      return;
    }
    dual_ = std::make_unique<DualSystem>(*dual_a_, fixed_alpha());
    scale_ = dual_->norm2_squared();
  }
  Eigen::MatrixXd dual_solution(const Eigen::MatrixXd& b, std::string& issue) const {
    if (dual_difference_) {
      issue = dual_difference_->issue();
      return dual_difference_->solve_columns(b);
    }
    issue = dual_->issue();
    return dual_->solve_columns(*dual_a_, b);
  }
  std::unique_ptr<StackedQr> stacked_qr(double alpha) const {
    return backend_ == Backend::dense ? std::make_unique<StackedQr>(a_dense_, l_dense_, alpha)
                                      : std::make_unique<StackedQr>(a_sparse_, l_, alpha);
  }
  // The least-squares form by the stacked QR (the fixed α's factorization from setup when it is that α).
  // `check_conditioning` (the fixed-parameter solve): a reciprocal condition estimate of the stacked matrix below
  // the unit roundoff is reported as singular to working precision.
  Eigen::VectorXd stacked_solution(const Eigen::VectorXd& b, double alpha, std::string& issue, bool check_conditioning,
                                   double* trace) const {
    std::unique_ptr<StackedQr> own;
    const StackedQr* qr = fixed_qr_.get();
    if (!qr || alpha != fixed_alpha()) {
      own = stacked_qr(alpha);
      qr = own.get();
    }
    const std::string failure = qr->failure();
    if (!failure.empty()) {
      issue = "tikhonov: the stacked least-squares matrix [A; sqrt(alpha) L] is singular at alpha = " + fmt(alpha) +
              " (" + failure + "); increase alpha";
      return Eigen::VectorXd::Zero(op().cols());
    }
    if (check_conditioning) {
      const double rc = qr->rcond();
      if (!(rc >= singular_rcond))
        issue = "tikhonov: the stacked least-squares matrix [A; sqrt(alpha) L] is singular to working precision at "
                "alpha = " + fmt(alpha) + ": reciprocal condition estimate " + fmt(rc) + " (min/max |diag R| of its " +
                (backend_ == Backend::dense ? "pivoted Householder QR" : "sparse QR") + ") is below the unit roundoff; increase alpha";
    }
    if (trace) *trace = backend_ == Backend::dense ? qr->influence_trace(a_dense_) : qr->influence_trace(a_sparse_);
    return qr->solve(b);
  }
  // `check_conditioning` (the fixed-parameter solve): a Cholesky factor whose reciprocal condition estimate is
  // below the unit roundoff is reported as not positive definite to working precision (the scan's smallest
  // alphas are bounded by alpha_min and keep their behaviour). `trace`, when given, receives the trace of the
  // influence matrix (for GCV).
  Eigen::VectorXd factored_solution(const Eigen::VectorXd& b, double alpha, std::string& issue,
                                    bool check_conditioning = false, double* trace = nullptr) const {
    if (!paper_) return stacked_solution(b, alpha, issue, check_conditioning, trace);
    const std::string not_pd = "tikhonov: the matrix A + alpha C is not positive definite at alpha = " + fmt(alpha);
    auto singular = [&](double rc, const char* how) {
      issue = not_pd + " to working precision: reciprocal condition estimate " + fmt(rc) + " (" + how +
              ") is below the unit roundoff; increase alpha";
    };
    // The paper form's influence matrix A (A + αC)⁻¹ has the trace of (A + αC)⁻¹ A.
    if (backend_ == Backend::dense) {
      const Eigen::MatrixXd k = g_dense_ + alpha * c_dense_;
      if (!symmetric_) {
        const Eigen::PartialPivLU<Eigen::MatrixXd> lu = k.partialPivLu();
        if (trace) *trace = lu.solve(g_dense_).trace();
        return lu.solve(b);
      }
      Eigen::LLT<Eigen::MatrixXd> llt(k);
      if (llt.info() != Eigen::Success) {
        issue = not_pd;
        return Eigen::VectorXd::Zero(op().cols());
      }
      if (check_conditioning) {
        const double rc = llt.rcond();
        if (!(rc >= singular_rcond)) singular(rc, "Eigen LLT");
      }
      if (trace) *trace = llt.solve(g_dense_).trace();
      return llt.solve(b);
    }
    const SpMat k = g_sparse_ + alpha * c_;
    if (!symmetric_) {
      Eigen::SparseLU<SpMat> lu(k);
      if (lu.info() != Eigen::Success) {
        issue = "tikhonov: sparse LU of A + alpha C failed at alpha = " + std::to_string(alpha);
        return Eigen::VectorXd::Zero(op().cols());
      }
      if (trace) *trace = Eigen::MatrixXd(lu.solve(Eigen::MatrixXd(g_sparse_))).trace();
      return lu.solve(b);
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
    if (trace) *trace = Eigen::MatrixXd(cholmod_->solve(Eigen::MatrixXd(g_sparse_))).trace();
    return cholmod_->solve(b);
  }

  bool paper_;
  int order_;
  double alpha_;
  Backend requested_, backend_ = Backend::spectral;
  double alpha_max_, alpha_min_;
  int alpha_count_;
  bool symmetric_ = false;
  double scale_ = 1.0;
  SpectralBasis basis_;                     // spectral, C = I
  std::unique_ptr<StandardForm> std_form_;  // spectral, least_squares with a difference L
  SpMat l_;                                 // L (C = L'L) unless spectral with C = I
  SpMat a_sparse_;                          // sparse least_squares: A for the stacked QR
  Eigen::MatrixXd a_dense_, l_dense_;
  std::unique_ptr<StackedQr> fixed_qr_;     // the fixed α's factorization (rule fixed)
  std::unique_ptr<DualSystem> dual_;        // backend dual, C = I: the factor of AAᵀ + αI
  std::unique_ptr<DualDifferenceSystem> dual_difference_;  // backend dual, a first difference L
  const Eigen::MatrixXd* dual_a_ = nullptr;  // backend dual: A (the operator's own dense storage, or a_dense_)
  SpMat c_, g_sparse_;                      // paper form: C and A
  Eigen::MatrixXd g_dense_, c_dense_;
  std::unique_ptr<Cholmod> cholmod_;        // factorize() mutates; see note in solve
};

}  // namespace

ParamSchema tikhonov_schema() {
  return {string_param("form", "least_squares",
                       "paper: (A + alpha C)x = b (4.7); least_squares: min ||Ax - b||^2 + alpha ||Lx||^2 (C = L'L; the "
                       "normal equations (A'A + alpha C)x = A'b are never formed)",
                       {"paper", "least_squares"}),
          string_param("regularizer", "identity",
                       "C = I, or C = L'L for a first/second difference L; first_difference_zero_ends: L includes the "
                       "links to known zeros beyond both ends, weighted by the operator's link weights (a channel's "
                       "viscosity: the minimum-viscous-dissipation prior)",
                       {"identity", "first_difference", "second_difference", "first_difference_zero_ends"}),
          number_param("alpha", 1e-6, "regularization parameter alpha (rule fixed)", 0.0, {}, true),
          string_param("backend", "auto",
                       "spectral: filter factors for every alpha from one decomposition (C = I: SVD/eigen, Kronecker-aware; "
                       "a difference L, least_squares only: standard form + SVD, the generalized SVD); dense: QR of "
                       "[A; sqrt(alpha) L] per alpha (paper: Cholesky/LU of A + alpha C); sparse: the same by Eigen's "
                       "SparseQR (paper: CHOLMOD/SparseLU); dual: x = A'(AA' + alpha I)^-1 b by Cholesky once (least_squares, "
                       "rule fixed; for a wide A; condition 1 + ||A||^2/alpha, a numerical issue below a reciprocal "
                       "1e-11; a first difference L: x = G A'y + N z, G the grounded (L'L)^-1 by CHOLMOD, N null(L)); auto: spectral unless A is sparse or the paper form has a difference C or a "
                       "non-symmetric A",
                       {"auto", "spectral", "dense", "sparse", "dual"}),
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
                       : be == "dual"   ? Tikhonov::Backend::dual
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
