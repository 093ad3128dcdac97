// Micro-benchmarks of the foundation kernels: the bond integral (App. A), the cell-list neighbour
// search, and one direct SPH step. Run: build/bench/closurelab_bench --benchmark_filter=Foundation
// (set OMP_NUM_THREADS=1 for per-core figures; the SPH step sets its own thread count, its third argument).
// items_per_second is bond integrals / pairs found / moving particle-steps per second.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <random>

#include "core/base/registry.hpp"
#include "core/sph/neighbour_search.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"
#include "strategies/kernels/gaussian_kernel.hpp"

using namespace closurelab;

namespace {

std::unique_ptr<Scene> channel(int ny, int nx) {
  return builtin_registry().scenes.create(json{{"name", "poiseuille-uniform"}, {"n_y", ny}, {"n_x", nx}}, "/scene");
}

}  // namespace

static void Foundation_BondIntegral(benchmark::State& state) {
  const double eta = 1.0 / 16, dx = 1.0 / 192;
  GaussianKernel k(eta);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-3 * eta, 3 * eta), bond(-3 * dx, 3 * dx);
  std::vector<std::array<Vec2, 3>> cases(4096);
  for (auto& c : cases) c = {Vec2(pos(rng), pos(rng)), Vec2(0, 0), Vec2(bond(rng), bond(rng))};
  std::size_t i = 0;
  double sum = 0;
  for (auto _ : state) {
    const auto& c = cases[i++ & 4095];
    sum += k.bond_integral(c[0], c[1], c[2]);
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(Foundation_BondIntegral);

static void Foundation_NeighbourSearch(benchmark::State& state) {
  const auto scene = channel(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const ParticleSystem ps = scene->make_particles();
  std::vector<std::int32_t> all(ps.size());
  for (std::size_t a = 0; a < ps.size(); ++a) all[a] = static_cast<std::int32_t>(a);
  std::size_t found = 0;
  for (auto _ : state) {
    const PairList p = find_pairs(ps, all, scene->box, 3.5 * scene->dx, [](int, int) { return true; });
    found = p.size();
    benchmark::DoNotOptimize(found);
  }
  state.counters["particles"] = static_cast<double>(ps.size());
  state.counters["pairs"] = static_cast<double>(found);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(ps.size()));
}
BENCHMARK(Foundation_NeighbourSearch)->Args({192, 12})->Args({192, 192})->Unit(benchmark::kMicrosecond);

// Args: n_y, n_x, OpenMP threads (the engine's team size is fixed at its construction). Wall-clock time, so that
// the 1- and 2-thread rows of one run compare.
static void Foundation_SphStep(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(2)));
  const PairKernelIsa isa = static_cast<PairKernelIsa>(state.range(3));
  if (!pair_kernel_isa_available(isa)) {
    state.SkipWithError("this pair kernel is not in this build or CPU");
    return;
  }
  const PairKernelIsa chosen = pair_kernel_isa();
  set_pair_kernel_isa(isa);
  const auto scene = channel(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  ParticleSystem ps = scene->make_particles();
  SphEngine engine(*scene, ps);
  const double dt = engine.time_step(0.25);
  for (int k = 0; k < 10; ++k) engine.step(dt);
  for (auto _ : state) engine.step(dt);
  state.counters["moving_particles"] = static_cast<double>(engine.moving().size());
  state.counters["pairs"] = static_cast<double>(engine.pair_count());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(engine.moving().size()));
  set_pair_kernel_isa(chosen);
}
// The last argument: the density pass's kernel loop compiled for the baseline (0), AVX2 (1) or AVX-512 (2), where
// available (PairKernelIsa); 96 x 96 is the peer benchmark's larger box (scripts/peer_bench.py).
BENCHMARK(Foundation_SphStep)
    ->ArgsProduct({{192}, {12, 192}, {1, 2}, {2}})
    ->ArgsProduct({{96}, {96}, {1}, {0, 1, 2}})
    ->ArgsProduct({{192}, {192}, {1}, {0, 1}})
    ->ArgNames({"n_y", "n_x", "threads", "isa"})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

// One direct SPH step per formulation, one thread, the best pair kernel: the standard WCSPH against the transport
// velocity on the same particles (the transport velocity's cost target: at most 1.5x a standard step per particle).
// Args: scene (0: taylor-green, doubly periodic; 1: lid-driven-cavity, walls on four sides with the transport
// velocity's wall condition, zero-velocity walls under the standard one), n, formulation (0: standard, 1:
// transport_velocity). items_per_second: moving particle-steps per second.
static void Foundation_SphStepFormulation(benchmark::State& state) {
  omp_set_num_threads(1);
  const char* name = state.range(0) == 0 ? "taylor-green" : "lid-driven-cavity";
  const auto scene = builtin_registry().scenes.create(json{{"name", name}, {"n", state.range(1)}}, "/scene");
  ParticleSystem ps = scene->make_particles();
  SphEngineOptions opt;
  opt.formulation = state.range(2) == 0 ? SphFormulation::standard : SphFormulation::transport_velocity;
  SphEngine engine(*scene, ps, opt);
  const double dt = engine.time_step(0.25);
  for (int k = 0; k < 10; ++k) engine.step(dt);
  for (auto _ : state) engine.step(dt);
  state.counters["moving_particles"] = static_cast<double>(engine.moving().size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(engine.moving().size()));
}
BENCHMARK(Foundation_SphStepFormulation)
    ->ArgsProduct({{0, 1}, {96}, {0, 1}})
    ->ArgNames({"scene", "n", "formulation"})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
