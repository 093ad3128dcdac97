// Micro-benchmarks of the stress quadratures: one evaluate() (the per-step cost of the reduced model's
// stress closure) of the exact pair sum (2.13) and of the coarse quadrature (5.27) at N = 1e4, 1e5, 1e6
// particles. N grows by widening the x-invariant Poiseuille strip (n_y = 192 rows, eta' = L_y/16, n_x =
// N/192 columns); the nodes are the solver's column mesh of spacing eta' (5.10). The coarse R-grid (one
// x-integrated column, stride_y = 4: the paper's N/N_C = 16 spacing) does not grow with N, so its time must
// stay flat; the exact quadrature reports its time per particle (particle_time = seconds per particle).
// Setup (pair search, bond weights) is outside the timed loop. Run:
//   OMP_NUM_THREADS=1 build/bench/closurelab_bench --benchmark_filter=Quadrature
// The coarse quadrature also runs at 1e7 (its setup never builds the particles). The exact one stops at 1e6:
// its tables (bond weights ~13 nodes x 12 B per pair, the engine's pair list and the per-call pair forces)
// would need ~35 GB at 1e7, beyond this 24 GB machine; its time per particle is flat from 1e4 to 1e6.
#include <benchmark/benchmark.h>

#include <functional>
#include <memory>

#include "core/averaging/averaging.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"
#include "strategies/quadrature/coarse_quadrature.hpp"
#include "strategies/quadrature/exact_quadrature.hpp"

using namespace closurelab;

namespace {

std::unique_ptr<Scene> strip(long particles) {
  const int ny = 192, nx = std::max<int>(12, static_cast<int>(particles / ny));
  return builtin_registry().scenes.create(json{{"name", "poiseuille-uniform"}, {"n_y", ny}, {"n_x", nx}}, "/scene");
}

VelocitySampler analytic_sampler(const Scene& s) {
  return [&s](const std::vector<Vec2>& pts) {
    Eigen::Matrix2Xd v = Eigen::Matrix2Xd::Zero(2, pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k)
      if (!s.is_wall(pts[k].y())) v(0, k) = s.analytic_vx(pts[k].y());
    return v;
  };
}

// The quadrature bound to the strip of `particles` particles, set up once per size (Google Benchmark calls a
// benchmark function several times while it sizes the iteration count; the setup is not what is measured).
struct Bound {
  long particles = -1;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<GaussianKernel> kernel;
  std::unique_ptr<StressQuadrature> q;
};

void run(benchmark::State& state, Bound& b, const std::function<std::unique_ptr<StressQuadrature>()>& make) {
  if (b.particles != state.range(0)) {
    b.q.reset();  // free the previous size's tables first
    b.scene = strip(state.range(0));
    b.kernel = std::make_unique<GaussianKernel>(b.scene->eta);
    b.q = make();
    b.q->setup(*b.scene, *b.kernel, column_mesh(b.scene->box, b.scene->eta), {"xy"});
    b.particles = state.range(0);
  }
  StressQuadrature& q = *b.q;
  const VelocitySampler sampler = analytic_sampler(*b.scene);
  QuadratureCost calls;
  double sink = 0.0;
  for (auto _ : state) {
    const QuadratureResult r = q.evaluate(sampler);
    calls.add(r);
    sink += r.stress.at("xy")[0];
  }
  benchmark::DoNotOptimize(sink);
  const double n = static_cast<double>(b.scene->nx) * b.scene->ny;
  state.counters["particles"] = n;
  state.counters["pair_forces_per_call"] =
      static_cast<double>(calls.pair_forces) / std::max(1L, calls.evaluations);
  state.counters["setup_s"] = q.setup_cost().setup_seconds;
  state.counters["particle_time"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

static void Quadrature_Exact(benchmark::State& state) {
  static Bound b;
  run(state, b, [] { return std::make_unique<ExactQuadrature>(); });
}
BENCHMARK(Quadrature_Exact)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

static void Quadrature_Coarse(benchmark::State& state) {
  static Bound b;
  run(state, b, [] { return std::make_unique<CoarseQuadrature>(0, 4); });
}
BENCHMARK(Quadrature_Coarse)->Arg(10000)->Arg(100000)->Arg(1000000)->Arg(10000000)->Unit(benchmark::kMicrosecond);
