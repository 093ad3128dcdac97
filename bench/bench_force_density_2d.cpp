// Micro-benchmarks of the 2D force-density model marched in time (core/reduced/force_density_2d.hpp) on the cylinder
// lattice at Re ~ 1 as experiments/cylinders/reduced_tvf_marched.json runs it (a = 0.2 L, g = 150, sound speed factor
// 10, no EOS background, zero-velocity walls; 16 x 16 coarse nodes at Delta = eta' = L/16, the reconstruction on
// 32 x 32, Tikhonov alpha = 1e-6 dual, the transport-velocity pair forces and the convective flux), against the
// lattice N = n² at a fixed coarse mesh:
//   ForceDensity2D_Setup/n         building the model (the maps assembled from the lattice: grows with N);
//   ForceDensity2D_MarchedStep/n   one forward-Euler step, i.e. one evaluation of the rate: three deconvolutions, the
//                                  pair forces' maps and the convective flux on the reconstruction's node pairs (its
//                                  cost does not grow with N).
// Run:
//   OMP_NUM_THREADS=1 build/bench/closurelab_bench --benchmark_filter=ForceDensity2D
#include <benchmark/benchmark.h>

#include <memory>

#include "core/base/registry.hpp"
#include "core/reduced/force_density_2d.hpp"

using namespace closurelab;

namespace {

struct Model {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<AveragingKernel> kernel;
  std::unique_ptr<Deconvolver> velocity, density;
  std::unique_ptr<Integrator> integrator;
  std::unique_ptr<ForceDensitySolver2D> solver;
};

std::unique_ptr<Model> build(int n) {
  const Registry& reg = builtin_registry();
  auto m = std::make_unique<Model>();
  const json scene = {{"name", "cylinder-lattice"},     {"n", n},
                      {"radius_over_length", 0.2},      {"g", 150},
                      {"sound_speed_factor", 10},       {"background_pressure_factor", 0.0},
                      {"wall_model", "zero_velocity"}};
  m->scene = reg.scenes.create(reg.scenes.resolve(scene, "/scene"), "/scene");
  m->kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", m->scene->eta}}, "/kernel");
  const json d = reg.deconvolvers.resolve(json{{"name", "tikhonov"}, {"alpha", 1e-6}, {"backend", "dual"}}, "/d");
  m->velocity = reg.deconvolvers.create(d, "/d");
  m->density = reg.deconvolvers.create(d, "/d");
  m->integrator = reg.integrators.create(json{{"name", "explicit"}}, "/integrator");
  const json solver = {{"pair_forces", "transport_velocity"}, {"convective_stress", true}};
  const ForceDensity2DOptions opt =
      force_density_2d_options_from(resolve_params(solver, force_density_2d_schema(), "/solver", {}));
  m->solver = std::make_unique<ForceDensitySolver2D>(*m->scene, *m->kernel, *m->velocity, *m->density, opt,
                                                     m->integrator.get());
  return m;
}

void ForceDensity2D_Setup(benchmark::State& state) {
  for (auto _ : state) {
    auto m = build(static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(m->solver.get());
  }
  state.counters["particles"] = static_cast<double>(state.range(0) * state.range(0));
}

void ForceDensity2D_MarchedStep(benchmark::State& state) {
  auto m = build(static_cast<int>(state.range(0)));
  // A tiny step: the state stays near rest, so every evaluation does the same work.
  const double dt = 1e-3 * m->solver->time_step();
  std::string issue;
  for (auto _ : state) {
    if (!m->solver->step(dt, issue)) state.SkipWithError(issue.c_str());
  }
  state.counters["particles"] = static_cast<double>(state.range(0) * state.range(0));
}

}  // namespace

BENCHMARK(ForceDensity2D_Setup)->Arg(48)->Arg(96)->Arg(192)->Unit(benchmark::kMillisecond);
BENCHMARK(ForceDensity2D_MarchedStep)->Arg(48)->Arg(96)->Arg(192)->Unit(benchmark::kMillisecond);
