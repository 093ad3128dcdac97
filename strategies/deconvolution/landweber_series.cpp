// Landweber deconvolution of order n exactly as the paper writes it:
//   x_n = Σ_{k=0}^{n} (I − A)^k b                                   (4.3), discretized as (4.9).
// Implemented by the recursion u_0 = b, u_{k+1} = u_k − A u_k, x_{n} = Σ_{k<=n} u_k; the residual of x_n is
// b − A x_n = (I − A)^{n+1} b = u_{n+1}, so each order costs one product with A and its residual is free.
// The series converges only when the spectrum of A lies in (0, 2); a sampled truncated Gaussian can have
// negative eigenvalues (DESIGN.md §6), which show as a growing ‖u_k‖: the scan reports that as an issue.
//
// lift = interpolation (the known zeros): for a rectangular A from a data mesh to a solution mesh (coarse_fine),
// the paper's own procedure, the series computed on the data mesh and interpolated to the solution mesh, with the
// series' operator the average of that interpolant: c_n = Σ_{k<=n} (I − A J)^k b, x_n = J c_n, J the (bi)linear
// interpolation of the data mesh at the solution mesh's nodes (periodic axes wrap, others clamp). The unknowns are
// the solution mesh's nodes only, so values beyond it (a channel's wall rows) enter A as their known zero, and the
// wall-surface nodes, where they are data, are data. Order 0 is J b (the average interpolated, (4.11)); the residual
// b − A x_n = (I − A J)^{n+1} b is again the next term of the recursion. lift = none is the series on a square A.
#include <limits>
#include <optional>
#include <vector>

#include "core/closure/reconstruction.hpp"

#include "strategies/deconvolution/deconvolver_base.hpp"
#include "strategies/deconvolution/deconvolvers.hpp"

namespace closurelab {
namespace {

constexpr double growth_tolerance = 1e-10;

class LandweberSeries : public DeconvolverBase {
 public:
  LandweberSeries(RuleConfig rule, int order, int max_order, bool report_residual, bool lift)
      : DeconvolverBase("landweber", rule, "order"), order_(order), max_order_(max_order),
        report_residual_(report_residual), lift_(lift) {}

 protected:
  bool scale_invariant() const override { return false; }  // the series (4.3) is for A ~ I, used as given
  std::string no_fit_hint() const override {
    return "the series (4.3) needs A's spectrum in (0, 2); a zero eigenvalue (or one at 2) leaves that part of the "
           "residual unchanged and adds it to x once per order (linear growth)";
  }
  void do_setup(const ForwardOperator& a) override {
    lifting_.reset();
    if (lift_) {
      lifting_ = interpolation_lifting(a);
      return;
    }
    if (!a.is_square())
      throw ConfigError("", "landweber (the series (4.3)/(4.9)) needs a square operator (coarse_coarse or fine_fine); "
                            "got " + std::to_string(a.rows()) + "x" + std::to_string(a.cols()) +
                            "; use lift = interpolation, landweber_relaxed or cgls");
  }

  DeconvolutionResult solve_fixed(const Eigen::VectorXd& b) const override {
    DeconvolutionResult r;
    if (!report_residual_) {
      // The bare series: n products with A for order n (the paper's cost), no residual (reported as NaN/null).
      Eigen::VectorXd x = b, u = b;
      for (int k = 1; k <= order_; ++k) {
        u -= product(u);
        x += u;
      }
      r.x = render(std::move(x));
      r.stats.residual_norm = std::numeric_limits<double>::quiet_NaN();
      r.stats.solution_norm = robust_norm(r.x);
      r.stats.chosen_parameter = order_;
      r.stats.iterations = order_;
      r.cost.matvecs = order_;
      r.stats.message = "residual not computed (report_residual = false); growth not monitored";
      return r;
    }
    bool stopped = false;
    do_scan_to(b, order_, [&](const ScanPoint& p) {
      if (p.parameter < order_ && p.issue.empty()) return true;
      r = result_from_scan_point(p);
      stopped = true;
      return false;
    });
    if (!stopped) throw NumericalError("landweber: series did not reach the requested order");
    return r;
  }

  void do_scan(const Eigen::VectorXd& b, const ScanVisitor& visit) const override { do_scan_to(b, max_order_, visit); }
  std::string scan_hint() const override { return "the rules scan the orders up to max_order"; }

 private:
  void do_scan_to(const Eigen::VectorXd& b, int max_order, const ScanVisitor& visit) const {
    Eigen::VectorXd x = b, u = b;
    double previous = robust_norm(b);
    const double floor = 1e-13 * robust_norm(b);
    for (int n = 0; n <= max_order; ++n) {
      Eigen::VectorXd r = u - product(u);  // u_{n+1} = (I − A) u_n = b − A x_n
      ScanPoint p;
      p.parameter = n;
      p.residual_norm = robust_norm(r);
      p.solution_norm = lifting_ ? robust_norm(render(x)) : robust_norm(x);  // ‖x_n‖ on the solution mesh
      p.matvecs = n + 1;
      p.last = n == max_order;
      if (!(p.residual_norm <= (1.0 + growth_tolerance) * previous + floor)) {  // growth beyond rounding
        p.issue = "landweber: growing mode at order " + std::to_string(n) + " (||(I-A)^k b|| grows from " +
                  std::to_string(previous) + " to " + std::to_string(p.residual_norm) +
                  "): A has eigenvalues outside (0, 2), e.g. a truncated sampled kernel";
        p.last = true;
      }
      p.solution = [this, &x] { return render(x); };
      if (!visit(p) || p.last) return;
      previous = p.residual_norm;
      x += r;
      u = std::move(r);
    }
  }
  // A u, or A J u with the lifting (u on the data mesh either way).
  Eigen::VectorXd product(const Eigen::VectorXd& u) const {
    return lifting_ ? op().apply(lifting_->apply(u)) : op().apply(u);
  }
  // The solution of the series' sum c: c itself, or J c on the solution mesh.
  Eigen::VectorXd render(Eigen::VectorXd c) const { return lifting_ ? lifting_->apply(c) : c; }

  // J = J_y ⊗ J_x: column i of J_x is the linear interpolant of the data axis's unit vector e_i at the solution
  // axis's nodes (a 1D operator has the 1 × 1 identity for y).
  static ForwardOperator interpolation_lifting(const ForwardOperator& a) {
    if (!a.data_mesh || !a.solution_mesh || a.dimension == 0)
      throw ConfigError("/lift", "lift = interpolation needs an operator built from a kernel on two meshes "
                                 "(a data mesh and a solution mesh); this one is a plain matrix");
    const auto axis = [](const UniformMesh1D& data, const UniformMesh1D& solution) {
      const UniformMesh1D single{0.0, 1.0, 1, false, 0.0};
      std::vector<Vec2> points;
      for (int j = 0; j < solution.count; ++j) points.emplace_back(solution.node(j), 0.0);
      Eigen::MatrixXd j(solution.count, data.count);
      for (int i = 0; i < data.count; ++i)
        j.col(i) = Reconstruction(TensorMesh2D{data, single}, 1, Eigen::VectorXd::Unit(data.count, i)).sample(points);
      return j;
    };
    const Eigen::MatrixXd jx = axis(a.data_mesh->x, a.solution_mesh->x);
    const Eigen::MatrixXd jy = a.dimension == 1 ? Eigen::MatrixXd::Identity(1, 1) : axis(a.data_mesh->y, a.solution_mesh->y);
    ForwardOperator j = ForwardOperator::from_kronecker(jy, jx);
    if (j.rows() != a.cols() || j.cols() != a.rows())
      throw ConfigError("/lift", "lift = interpolation: the meshes give a " + std::to_string(j.rows()) + "x" +
                                     std::to_string(j.cols()) + " interpolation for a " + std::to_string(a.rows()) +
                                     "x" + std::to_string(a.cols()) + " operator (its unknowns are not its solution mesh)");
    return j;
  }

  int order_, max_order_;
  bool report_residual_, lift_;
  std::optional<ForwardOperator> lifting_;  // J, with lift = interpolation
};

}  // namespace

ParamSchema landweber_series_schema() {
  return {integer_param("order", 1, "series order n of (4.3)/(4.9) (rule fixed)", 0, 100000),
          integer_param("max_order", 500, "largest order tried by the discrepancy/lcurve rules", 0, 1000000),
          bool_param("report_residual", true,
                     "rule fixed: also compute b - A x_n (one more product, and the growth check); false = n products"),
          string_param("lift", "none",
                       "none: the series on a square A (coarse_coarse, fine_fine); interpolation: the series on the "
                       "data mesh with A J and x_n = J c_n, J the linear interpolation onto the solution mesh (any "
                       "discretization, e.g. coarse_fine: the unknowns are the solution mesh's nodes, values beyond "
                       "it such as a channel's wall rows their known zero)",
                       {"none", "interpolation"}),
          rule_param({"fixed", "discrepancy", "lcurve"}, "fixed"), safety_param()};
}

std::unique_ptr<Deconvolver> make_landweber_series(const json& p) {
  return std::make_unique<LandweberSeries>(RuleConfig::from_json(p), p.at("order").get<int>(),
                                           p.at("max_order").get<int>(), p.at("report_residual").get<bool>(),
                                           p.at("lift").get<std::string>() == "interpolation");
}

}  // namespace closurelab
