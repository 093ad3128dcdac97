#include "experiments/testproblems/ill_posed_problems.hpp"

#include <gsl/gsl_integration.h>

#include <cmath>
#include <memory>
#include <functional>
#include <random>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

namespace closurelab {

namespace {

// ∫_lo^hi f by GSL's adaptive Gauss–Kronrod (QAG, 61 points), with `breaks` to split at known kinks.
double integrate(const std::function<double(double)>& f, double lo, double hi) {
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(2000);
  gsl_function g;
  g.function = [](double t, void* p) { return (*static_cast<const std::function<double(double)>*>(p))(t); };
  g.params = const_cast<std::function<double(double)>*>(&f);
  double result = 0, err = 0;
  gsl_integration_qag(&g, lo, hi, 1e-14, 1e-12, 2000, GSL_INTEG_GAUSS61, w, &result, &err);
  gsl_integration_workspace_free(w);
  return result;
}

// Two Gaussian bumps on [0, 1] (vanishing to 1e-15 at the ends).
constexpr double c1 = 0.38, w1 = 0.07, a1 = 1.0, c2 = 0.64, w2 = 0.045, a2 = 0.6;
double bumps(double y) { return a1 * std::exp(-std::pow((y - c1) / w1, 2)) + a2 * std::exp(-std::pow((y - c2) / w2, 2)); }
// φ_η * bump for the Gaussian factor φ(t) = exp(−t²/η²)/(√π η): closed form.
double averaged_bumps(double x, double eta) {
  auto one = [&](double a, double c, double w) {
    const double s2 = w * w + eta * eta;
    return a * w / std::sqrt(s2) * std::exp(-(x - c) * (x - c) / s2);
  };
  return one(a1, c1, w1) + one(a2, c2, w2);
}

Eigen::VectorXd sample(const std::function<double(double)>& f, const UniformMesh1D& m) {
  Eigen::VectorXd v(m.count);
  for (int i = 0; i < m.count; ++i) v(i) = f(m.node(i));
  return v;
}

IllPosedProblem midpoint_problem(std::string name, int n, double lo, double hi,
                                 const std::function<double(double, double)>& kernel,
                                 const std::function<double(double)>& solution,
                                 const std::function<double(double)>& data) {
  if (n < 2) throw ConfigError("/n", "problem size must be at least 2");
  const UniformMesh1D m = UniformMesh1D::cell_centred(lo, hi - lo, n, false);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = m.spacing * kernel(m.node(i), m.node(j));
  IllPosedProblem p{std::move(name), ForwardOperator::from_dense(std::move(a)), sample(data, m), sample(solution, m), {}};
  p.info = {{"n", n}, {"interval", {lo, hi}}, {"quadrature", "midpoint"}};
  return p;
}

}  // namespace

IllPosedProblem make_gaussian_problem(const GaussianProblemSpec& s) {
  if (s.coarse_count < 2) throw ConfigError("/coarse_count", "need at least 2 coarse cells");
  if (!(s.eta_over_h > 0)) throw ConfigError("/eta_over_h", "must be > 0");
  if (s.fine_ratio < 1) throw ConfigError("/fine_ratio", "must be >= 1");
  const UniformMesh1D coarse = UniformMesh1D::cell_centred(0.0, 1.0, s.coarse_count, s.periodic);
  const UniformMesh1D fine = UniformMesh1D::cell_centred(0.0, 1.0, s.coarse_count * s.fine_ratio, s.periodic);
  const double eta = s.eta_over_h * coarse.spacing;
  std::unique_ptr<AveragingKernel> kernel;
  if (s.kernel == "gaussian")
    kernel = std::make_unique<GaussianKernel>(eta);
  else if (s.kernel == "cutoff_gaussian")
    kernel = std::make_unique<CutoffGaussianKernel>(eta, s.cutoff_in_eta);
  else
    throw ConfigError("/kernel", "unknown kernel '" + s.kernel + "'; known: gaussian, cutoff_gaussian");
  IllPosedProblem p;
  p.name = "gaussian_averaging";
  p.a = make_averaging_operator_1d(*kernel, coarse, fine, s.discretization, OperatorStorage::dense);
  const UniformMesh1D& data_mesh = p.a.data_mesh->x;
  const UniformMesh1D& sol_mesh = p.a.solution_mesh->x;
  p.x_true = sample(bumps, sol_mesh);
  if (s.kernel == "gaussian") {
    p.b_exact = sample([eta](double x) { return averaged_bumps(x, eta); }, data_mesh);
  } else {
    const double rc = kernel->support_radius();
    const AveragingKernel& k = *kernel;
    p.b_exact = sample([&](double x) { return integrate([&](double y) { return k.factor(x - y) * bumps(y); }, x - rc, x + rc); },
                       data_mesh);
  }
  p.info = {{"kernel", s.kernel},       {"eta", eta},
            {"coarse_count", s.coarse_count}, {"eta_over_h", s.eta_over_h},
            {"fine_ratio", s.fine_ratio}, {"discretization", to_string(s.discretization)},
            {"rows", p.a.rows()},         {"cols", p.a.cols()}};
  if (s.kernel == "cutoff_gaussian") p.info["cutoff_in_eta"] = s.cutoff_in_eta;
  return p;
}

IllPosedProblem make_shaw_problem(int n) {
  const double pi = M_PI;
  auto kernel = [pi](double s, double t) {
    const double u = pi * (std::sin(s) + std::sin(t));
    const double sinc = std::abs(u) < 1e-12 ? 1.0 : std::sin(u) / u;
    return std::pow(std::cos(s) + std::cos(t), 2) * sinc * sinc;
  };
  auto solution = [](double t) { return 2.0 * std::exp(-6.0 * (t - 0.8) * (t - 0.8)) + std::exp(-2.0 * (t + 0.5) * (t + 0.5)); };
  auto data = [&](double s) { return integrate([&](double t) { return kernel(s, t) * solution(t); }, -pi / 2, pi / 2); };
  IllPosedProblem p = midpoint_problem("shaw", n, -pi / 2, pi / 2, kernel, solution, data);
  p.info["data"] = "GSL QAG quadrature of the continuous kernel";
  return p;
}

IllPosedProblem make_deriv2_problem(int n) {
  auto kernel = [](double s, double t) { return s < t ? s * (t - 1.0) : t * (s - 1.0); };
  IllPosedProblem p = midpoint_problem("deriv2", n, 0.0, 1.0, kernel, [](double t) { return t; },
                                       [](double s) { return (s * s * s - s) / 6.0; });
  p.info["data"] = "closed form (s^3 - s)/6";
  return p;
}

IllPosedProblem make_phillips_problem(int n) {
  auto f = [](double x) { return std::abs(x) < 3.0 ? 1.0 + std::cos(M_PI * x / 3.0) : 0.0; };
  auto data = [](double s) {
    const double a = std::abs(s);
    if (a >= 6.0) return 0.0;
    return (6.0 - a) * (1.0 + 0.5 * std::cos(M_PI * s / 3.0)) + 9.0 / (2.0 * M_PI) * std::sin(M_PI * a / 3.0);
  };
  IllPosedProblem p = midpoint_problem("phillips", n, -6.0, 6.0, [f](double s, double t) { return f(s - t); }, f, data);
  p.info["data"] = "closed form";
  return p;
}

ParamSchema ill_posed_problem_schema() {
  return {integer_param("n", 64, "size of the classic problems (shaw, deriv2, phillips)", 2, 5000),
          string_param("kernel", "gaussian", "gaussian_averaging: averaging kernel", {"gaussian", "cutoff_gaussian"}),
          number_param("cutoff_in_eta", 2.0, "gaussian_averaging with cutoff_gaussian: truncation radius / eta", 0.5, 20.0),
          integer_param("coarse_count", 64, "gaussian_averaging: coarse cells on [0, 1]", 2, 100000),
          number_param("eta_over_h", 2.0, "gaussian_averaging: eta in coarse spacings (a window wider than 1000 spacings averages everything to one number)", 0.0, 1000.0, true),
          integer_param("fine_ratio", 4, "gaussian_averaging: coarse / fine spacing", 1, 1000),
          string_param("discretization", "coarse_coarse", "gaussian_averaging: discretization (section 4.2)",
                       {"coarse_coarse", "coarse_fine", "fine_fine"}),
          bool_param("periodic", false, "gaussian_averaging: periodic [0, 1]")};
}

void check_ill_posed_problem_size(const json& p, const std::string& path) {
  // Gaussian averaging: the operator, its SVD factors and work arrays, about four dense copies of rows x cols.
  const double coarse = p.at("coarse_count").get<double>(), fine = coarse * p.at("fine_ratio").get<double>();
  const std::string d = p.at("discretization").get<std::string>();
  const double rows = d == "fine_fine" ? fine : coarse, cols = d == "coarse_coarse" ? coarse : fine;
  check_allocation(rows * cols, 4.0 * sizeof(double),
                   "a " + json(rows).dump() + " x " + json(cols).dump() + " dense test problem and its factorization",
                   path + "/coarse_count");
}

IllPosedProblem make_ill_posed_problem(const json& config, const std::string& path) {
  if (!config.is_object() || !config.contains("name") || !config.at("name").is_string())
    throw ConfigError(path + "/name", "a problem needs a string \"name\": gaussian_averaging, shaw, deriv2, phillips");
  const std::string name = config.at("name").get<std::string>();
  const json p = resolve_params(config, ill_posed_problem_schema(), path);
  const int n = p.at("n").get<int>();
  if (name == "shaw") return make_shaw_problem(n);
  if (name == "deriv2") return make_deriv2_problem(n);
  if (name == "phillips") return make_phillips_problem(n);
  if (name != "gaussian_averaging")
    throw ConfigError(path + "/name", "unknown problem '" + name + "'; known: gaussian_averaging, shaw, deriv2, phillips");
  GaussianProblemSpec s;
  s.kernel = p.at("kernel").get<std::string>();
  s.cutoff_in_eta = p.at("cutoff_in_eta").get<double>();
  s.coarse_count = p.at("coarse_count").get<int>();
  s.eta_over_h = p.at("eta_over_h").get<double>();
  s.fine_ratio = p.at("fine_ratio").get<int>();
  s.discretization = parse_discretization(p.at("discretization").get<std::string>(), path + "/discretization");
  s.periodic = p.at("periodic").get<bool>();
  check_ill_posed_problem_size(p, path);
  try {
    return make_gaussian_problem(s);
  } catch (const ConfigError& e) {
    throw ConfigError(path + e.path(), e.message());
  }
}

Eigen::VectorXd add_noise(const Eigen::VectorXd& b, double relative_level, std::uint64_t seed, double& delta) {
  if (!(relative_level >= 0) || !std::isfinite(relative_level)) throw ConfigError("/noise", "noise level must be >= 0");
  if (relative_level == 0) {
    delta = 0;
    return b;
  }
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd e(b.size());
  for (Eigen::Index i = 0; i < b.size(); ++i) e(i) = normal(rng);
  e *= relative_level * b.norm() / e.norm();
  delta = e.norm();
  return b + e;
}

}  // namespace closurelab
