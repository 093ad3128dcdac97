// Truncated SVD (§4.2): project onto the singular vectors of the k largest singular values,
//   x_k = Σ_{i<=k} (u_iᵀ b / σ_i) v_i,
// truncated by index k or by a relative threshold σ_i >= t σ_1, or by a rule scanning k = 1, 2, ...
// On a Kronecker operator A = A_y ⊗ A_x the SVD is that of the factors (σ = σ_y σ_x), so setup is
// O(n_x³ + n_y³) and a solve is four small dense products.
#include <algorithm>
#include <vector>

#include "core/closure/spectral_basis.hpp"
#include "strategies/deconvolution/deconvolver_base.hpp"
#include "strategies/deconvolution/deconvolvers.hpp"

namespace closurelab {
namespace {

class TruncatedSvd : public DeconvolverBase {
 public:
  TruncatedSvd(RuleConfig rule, bool by_index, int k, double threshold, int max_rank)
      : DeconvolverBase("tsvd", rule, "k"), by_index_(by_index), k_(k), threshold_(threshold), max_rank_(max_rank) {}

 protected:
  void do_setup(const ForwardOperator& a) override {
    basis_ = SpectralBasis(a, SpectralBasis::Kind::svd);
    const int n = static_cast<int>(basis_.sigma().size());
    if (rule().rule == ParameterRule::fixed && by_index_ && k_ > n)
      throw ConfigError("/k", "truncation index " + std::to_string(k_) + " exceeds the number of singular values " +
                                  std::to_string(n));
  }

  DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const override {
    const Eigen::VectorXd beta = basis_.coefficients(b);
    int k = k_;
    if (!by_index_) {
      const double smax = std::abs(basis_.sigma()(basis_.order()(0)));
      k = 0;
      while (k < basis_.order().size() && std::abs(basis_.sigma()(basis_.order()(k))) >= threshold_ * smax) ++k;
    }
    DeconvolutionResult r;
    r.x = basis_.synthesize(filtered(beta, k));
    r.cost.matvecs = 2;
    finish_fixed(r, b, k);
    // Singular values at or below the rank tolerance max(m, n) ε σ_1 are rounding noise: dividing by them
    // amplifies the data's rounding by ~1/ε (a rank-3 5x5 matrix with k = 5 gave ||x|| = 5e15).
    if (k > basis_.numerical_rank()) {
      r.status = DeconvolutionStatus::numerical_issue;
      r.stats.message = "tsvd: " + std::string(by_index_ ? "k = " : "the threshold keeps k = ") + std::to_string(k) +
                        " singular values, above the numerical rank " + std::to_string(basis_.numerical_rank()) +
                        " (singular values <= max(m, n) eps sigma_1 are rounding noise); use k <= " +
                        std::to_string(basis_.numerical_rank()) + (by_index_ ? "" : " (a larger threshold)") +
                        " or a rule";
    }
    return r;
  }

  std::string scan_hint() const override {
    return "the rules scan k from 1 to max_rank or the numerical rank, whichever is smaller";
  }
  void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const override {
    const Eigen::VectorXd beta = basis_.coefficients(b);
    const int n = static_cast<int>(basis_.order().size());
    // The family stops at the numerical rank: beyond it the "singular values" are rounding noise.
    const int rank = basis_.numerical_rank();
    const int kmax = std::max(1, max_rank_ > 0 ? std::min(max_rank_, rank) : rank);
    const double m = static_cast<double>(basis_.data_size());
    // ‖r_k‖² = Σ_{j>k} β_j² + ‖b_⊥‖², summed from the tail (no cancellation); b_⊥ = 0 unless A has more
    // rows than singular values.
    std::vector<double> tail(static_cast<size_t>(n) + 1, 0.0);
    for (int j = n - 1; j >= 0; --j) {
      const int i = basis_.order()(j);
      tail[static_cast<size_t>(j)] = tail[static_cast<size_t>(j) + 1] + beta(i) * beta(i);  // σ = 0 modes stay in r
    }
    const double b_perp2 = basis_.data_size() > n ? std::max(b.squaredNorm() - tail[0], 0.0) : 0.0;
    double x2 = 0.0;
    for (int k = 1; k <= kmax; ++k) {
      const int i = basis_.order()(k - 1);
      const double s = basis_.sigma()(i);
      if (s != 0.0) x2 += (beta(i) / s) * (beta(i) / s);
      const double r2 = tail[static_cast<size_t>(k)] + b_perp2;
      ScanPoint p;
      p.parameter = k;
      p.residual_norm = std::sqrt(r2);
      p.solution_norm = std::sqrt(x2);
      p.gcv = m > k ? r2 / ((m - k) * (m - k)) : -1.0;
      p.matvecs = 2;
      p.last = k == kmax;
      p.solution = [this, &beta, k] { return basis_.synthesize(filtered(beta, k)); };
      if (!visit(p)) return;
    }
  }

 private:
  Eigen::VectorXd filtered(const Eigen::VectorXd& beta, int k) const {
    Eigen::VectorXd c = Eigen::VectorXd::Zero(beta.size());
    for (int j = 0; j < k; ++j) {
      const int i = basis_.order()(j);
      if (basis_.sigma()(i) != 0.0) c(i) = beta(i) / basis_.sigma()(i);
    }
    return c;
  }
  bool by_index_;
  int k_;
  double threshold_;
  int max_rank_;
  SpectralBasis basis_;
};

}  // namespace

ParamSchema tsvd_schema() {
  return {string_param("truncation", "index", "truncate by index k or by relative threshold", {"index", "threshold"}),
          integer_param("k", 10, "number of singular values kept (truncation index, rule fixed)", 1, 100000000),
          number_param("threshold", 1e-8, "keep sigma_i >= threshold * sigma_1 (truncation threshold)", 0.0, 1.0, true),
          integer_param("max_rank", 0, "largest k scanned by the rules (0 = all)", 0, 100000000),
          rule_param({"fixed", "discrepancy", "gcv", "lcurve"}, "fixed"), safety_param()};
}

std::unique_ptr<Deconvolver> make_tsvd(const json& p) {
  return std::make_unique<TruncatedSvd>(RuleConfig::from_json(p), p.at("truncation").get<std::string>() == "index",
                                        p.at("k").get<int>(), p.at("threshold").get<double>(),
                                        p.at("max_rank").get<int>());
}

}  // namespace closurelab
