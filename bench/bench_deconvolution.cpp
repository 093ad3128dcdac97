// Deconvolution micro-benchmarks: setup and solve per strategy on coarse tensor meshes 16²…256²
// (Kronecker operators A = A_y ⊗ A_x, η = 2h), and fine–fine operators up to 10⁴ unknowns (Kronecker, and
// sparse cut-off with CHOLMOD for Tikhonov with a difference regularizer). Counters: unknowns, matvecs.
// Run: OMP_NUM_THREADS=1 closurelab_bench --benchmark_filter=Deconv
// (one thread: Eigen's OpenMP products otherwise fight for the cores of a shared machine).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>

#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/base/registry.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {

TensorMesh2D square_mesh(int n, bool periodic = false) {
  return {UniformMesh1D::cell_centred(0, 1, n, periodic), UniformMesh1D::cell_centred(0, 1, n, periodic)};
}

ForwardOperator coarse_operator(int n, OperatorStorage storage = OperatorStorage::kronecker) {
  const TensorMesh2D m = square_mesh(n);
  const GaussianKernel k(2.0 / n);
  return make_averaging_operator_2d(k, m, m, Discretization::coarse_coarse, storage, 1e-14);
}

Eigen::VectorXd smooth_data(const ForwardOperator& a) {
  Eigen::VectorXd x(a.cols());
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = std::sin(0.01 * static_cast<double>(i)) + 1.0;
  return a.apply(x);
}

const json& method(const std::string& name) {
  static const std::map<std::string, json> m = {
      {"tsvd", {{"name", "tsvd"}, {"k", 8}}},
      {"tikhonov", {{"name", "tikhonov"}, {"alpha", 1e-4}}},
      {"tikhonov_paper", {{"name", "tikhonov"}, {"alpha", 1e-4}, {"form", "paper"}}},
      {"landweber1", {{"name", "landweber"}, {"order", 1}}},
      {"landweber2", {{"name", "landweber"}, {"order", 2}}},
      {"landweber1_bare", {{"name", "landweber"}, {"order", 1}, {"report_residual", false}}},
      {"landweber2_bare", {{"name", "landweber"}, {"order", 2}, {"report_residual", false}}},
      {"landweber_relaxed", {{"name", "landweber_relaxed"}, {"iterations", 50}}},
      {"cg", {{"name", "cg"}, {"iterations", 50}, {"tolerance", 0.0}}},
      {"cgls", {{"name", "cgls"}, {"iterations", 50}, {"tolerance", 0.0}}},
      {"tikhonov_d1_cholmod", {{"name", "tikhonov"}, {"alpha", 1e-4}, {"regularizer", "first_difference"}, {"backend", "sparse"}}}};
  return m.at(name);
}

void setup_bench(benchmark::State& state, const std::string& name) {
  const ForwardOperator a = coarse_operator(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto d = builtin_registry().deconvolvers.create(method(name), "/m");
    d->setup(a);
    benchmark::DoNotOptimize(d);
  }
  state.counters["unknowns"] = static_cast<double>(a.cols());
}

void solve_bench(benchmark::State& state, const std::string& name, const ForwardOperator& a) {
  const Eigen::VectorXd b = smooth_data(a);
  auto d = builtin_registry().deconvolvers.create(method(name), "/m");
  d->setup(a);
  long matvecs = 0;
  for (auto _ : state) {
    const DeconvolutionResult r = d->solve(b);
    matvecs = r.cost.matvecs;
    benchmark::DoNotOptimize(r.x.data());
  }
  state.counters["unknowns"] = static_cast<double>(a.cols());
  state.counters["matvecs"] = static_cast<double>(matvecs);
  // Seconds per solve per 1000 unknowns (printed with a unit, e.g. "2.1us").
  state.counters["per_1000_unknowns"] = benchmark::Counter(
      static_cast<double>(a.cols()) / 1000.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void coarse_solve(benchmark::State& state, const std::string& name) {
  solve_bench(state, name, coarse_operator(static_cast<int>(state.range(0))));
}

// One separable convolution A x (the unit of the Landweber target: order n costs n + 1 of these).
void BM_DeconvApplyKronecker(benchmark::State& state) {
  const ForwardOperator a = coarse_operator(static_cast<int>(state.range(0)));
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(a.cols());
  for (auto _ : state) benchmark::DoNotOptimize(a.apply(x).data());
  state.counters["unknowns"] = static_cast<double>(a.cols());
}
BENCHMARK(BM_DeconvApplyKronecker)->RangeMultiplier(2)->Range(16, 256)->Unit(benchmark::kMicrosecond);

#define COARSE_SETUP(NAME, MAXN)                                                                    \
  void BM_DeconvSetup_##NAME(benchmark::State& s) { setup_bench(s, #NAME); }                        \
  BENCHMARK(BM_DeconvSetup_##NAME)->RangeMultiplier(2)->Range(16, MAXN)->Unit(benchmark::kMillisecond);
#define COARSE_SOLVE(NAME, MAXN)                                                                    \
  void BM_DeconvSolve_##NAME(benchmark::State& s) { coarse_solve(s, #NAME); }                       \
  BENCHMARK(BM_DeconvSolve_##NAME)->RangeMultiplier(2)->Range(16, MAXN)->Unit(benchmark::kMicrosecond);

COARSE_SETUP(tsvd, 256)
COARSE_SETUP(tikhonov, 256)
COARSE_SETUP(tikhonov_paper, 256)
COARSE_SOLVE(tsvd, 256)
COARSE_SOLVE(tikhonov, 256)
COARSE_SOLVE(tikhonov_paper, 256)
COARSE_SOLVE(landweber1, 256)
COARSE_SOLVE(landweber2, 256)
COARSE_SOLVE(landweber1_bare, 256)
COARSE_SOLVE(landweber2_bare, 256)
COARSE_SOLVE(landweber_relaxed, 128)
COARSE_SOLVE(cg, 128)
COARSE_SOLVE(cgls, 128)

// Fine–fine: a 20 × 20 coarse mesh (η = 2H = 0.1) refined by r = 1…5 (up to 100² = 10⁴ unknowns). The sparse
// variant uses the Gaussian cut off at 2η (CutoffGaussianKernel), so A and AᵀA are genuinely sparse.
ForwardOperator fine_fine_operator(int ratio, OperatorStorage storage) {
  const TensorMesh2D c = square_mesh(20), f = square_mesh(20 * ratio);
  if (storage == OperatorStorage::sparse) {
    const CutoffGaussianKernel k(0.1, 2.0);
    return make_averaging_operator_2d(k, c, f, Discretization::fine_fine, storage, 0.0);
  }
  const GaussianKernel k(0.1);
  return make_averaging_operator_2d(k, c, f, Discretization::fine_fine, storage, 1e-14);
}
void BM_DeconvFineFineSetupSolve_tsvd(benchmark::State& state) {
  const ForwardOperator a = fine_fine_operator(static_cast<int>(state.range(0)), OperatorStorage::kronecker);
  const Eigen::VectorXd b = smooth_data(a);
  for (auto _ : state) {
    auto d = builtin_registry().deconvolvers.create(method("tsvd"), "/m");
    d->setup(a);
    benchmark::DoNotOptimize(d->solve(b).x.data());
  }
  state.counters["unknowns"] = static_cast<double>(a.cols());
}
BENCHMARK(BM_DeconvFineFineSetupSolve_tsvd)->DenseRange(1, 5, 2)->Unit(benchmark::kMillisecond);
void BM_DeconvFineFineSolve_cgls(benchmark::State& state) {
  solve_bench(state, "cgls", fine_fine_operator(static_cast<int>(state.range(0)), OperatorStorage::kronecker));
}
BENCHMARK(BM_DeconvFineFineSolve_cgls)->DenseRange(1, 5, 2)->Unit(benchmark::kMillisecond);
void BM_DeconvFineFineSetupSolve_cholmod(benchmark::State& state) {
  const ForwardOperator a = fine_fine_operator(static_cast<int>(state.range(0)), OperatorStorage::sparse);
  const Eigen::VectorXd b = smooth_data(a);
  for (auto _ : state) {
    auto d = builtin_registry().deconvolvers.create(method("tikhonov_d1_cholmod"), "/m");
    d->setup(a);
    benchmark::DoNotOptimize(d->solve(b).x.data());
  }
  state.counters["unknowns"] = static_cast<double>(a.cols());
  state.counters["nonzeros"] = static_cast<double>(a.sparse().nonZeros());
}
BENCHMARK(BM_DeconvFineFineSetupSolve_cholmod)->DenseRange(1, 3, 1)->Unit(benchmark::kMillisecond);

}  // namespace
