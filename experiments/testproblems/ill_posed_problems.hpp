#pragma once
// Test problems for deconvolution (DESIGN.md §7 rung 5), each with its exact solution and exact data made
// WITHOUT the inverse crime: b comes from the analytic integral or an adaptive GSL quadrature of the continuous
// kernel, never from the matrix used for the inversion.
//   gaussian_averaging  R_η (4.1) on [0,1] (coarse–coarse / coarse–fine / fine–fine, §4.2) of two Gaussian
//                       bumps; data from the closed-form Gaussian convolution (or adaptive quadrature for the
//                       cut-off Gaussian, which can have negative eigenvalues when sampled, DESIGN.md §6).
//   shaw                C. B. Shaw Jr., J. Math. Anal. Appl. 37 (1972): K(s,t) = (cos s + cos t)² (sin u/u)²,
//                       u = π(sin s + sin t), s,t ∈ [−π/2, π/2]; x(t) = 2e^{−6(t−0.8)²} + e^{−2(t+0.5)²}
//                       (the solution of Hansen's Regularization Tools `shaw`).
//   deriv2              the Green's function of −d²/dx² on [0,1] with zero ends: K(s,t) = s(t−1) for s < t,
//                       t(s−1) for s >= t; x(t) = t, b(s) = (s³ − s)/6 (Regularization Tools `deriv2`, example 1).
//   phillips            D. L. Phillips, J. ACM 9 (1962): f(x) = 1 + cos(πx/3) on |x| < 3, else 0;
//                       K(s,t) = f(s − t), x = f, b(s) = (6 − |s|)(1 + cos(πs/3)/2) + 9/(2π) sin(π|s|/3) on [−6, 6].
// The classic problems are discretized by the midpoint rule (collocation at midpoints), A_ij = h K(s_i, t_j).
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "core/closure/forward_operator.hpp"
#include "core/base/params.hpp"

namespace closurelab {

struct IllPosedProblem {
  std::string name;
  ForwardOperator a;
  Eigen::VectorXd b_exact;  // exact data at the data nodes
  Eigen::VectorXd x_true;   // exact solution at the solution nodes
  json info;                // sizes, η, discretization, ...
};

struct GaussianProblemSpec {
  std::string kernel = "gaussian";  // "gaussian" or "cutoff_gaussian"
  double cutoff_in_eta = 2.0;       // cutoff_gaussian only
  int coarse_count = 64;            // coarse cells on [0, 1]
  double eta_over_h = 2.0;          // η in units of the coarse spacing H
  int fine_ratio = 4;               // fine spacing h = H / fine_ratio
  Discretization discretization = Discretization::coarse_coarse;
  bool periodic = false;
};

IllPosedProblem make_gaussian_problem(const GaussianProblemSpec& spec);
IllPosedProblem make_shaw_problem(int n);
IllPosedProblem make_deriv2_problem(int n);
IllPosedProblem make_phillips_problem(int n);

// Builds a problem from {"name": "gaussian_averaging"|"shaw"|"deriv2"|"phillips", ...}; ConfigError by path.
IllPosedProblem make_ill_posed_problem(const json& config, const std::string& path);
ParamSchema ill_posed_problem_schema();
// Refuses (ConfigError at path/coarse_count) a resolved gaussian_averaging problem whose dense operator and
// factorization would not fit the memory limit; cheap, for validation.
void check_ill_posed_problem_size(const json& resolved_problem, const std::string& path);

// Adds Gaussian white noise scaled to ‖e‖₂ = relative_level ‖b‖₂ (std::mt19937_64 seeded with `seed`);
// returns the noisy data and writes δ = ‖e‖₂.
Eigen::VectorXd add_noise(const Eigen::VectorXd& b, double relative_level, std::uint64_t seed, double& delta);

}  // namespace closurelab
