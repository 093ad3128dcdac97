// Micro-benchmarks of the one-dimensional reduced model (core/reduced/meso_solver.hpp), the near-wall formulation
// of the committed speed-up table (experiments/paper/speed_up.json: the force-density balance with every node
// evolved, backward Euler, the coarse–fine Tikhonov closure with the viscosity-weighted zero-end first difference,
// α = 1e-6, here on the `dual` backend) on poiseuille-uniform.
//
// Reduced1D_NearWallSetup: the solver's construction (the forward operator, the deconvolver's factorization, the
// force-density map probed on the narrowest strip, the averaged body force and density). Reduced1D_NearWallSteady:
// setup and the run to steady state, what a user waits for. Arguments (n_y, m): the lattice's rows and η' = L/m,
// so the coarse mesh has about m nodes; n_y = 192 … 1536 at m = 16 is the cost against N at fixed N_C, m = 16 … 128
// at n_y = 1536 against N_C at fixed N. A third argument 1 puts the closure on Tikhonov's `auto` backend (spectral
// here, the committed tables' choice) instead of `dual`: the same solution, another factorisation; 2 finds the
// steady state by the `newton` integrator (one solve of the probed Jacobian) instead of marching by backward Euler.
// Run:
//   OMP_NUM_THREADS=1 build/bench/closurelab_bench --benchmark_filter=Reduced1D
#include <benchmark/benchmark.h>

#include <memory>

#include "core/base/registry.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/sph/scene.hpp"

using namespace closurelab;

namespace {

struct Column {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<AveragingKernel> kernel;
  std::unique_ptr<Deconvolver> deconvolver;
  std::unique_ptr<StressQuadrature> quadrature;
  std::unique_ptr<Integrator> integrator;
  std::unique_ptr<MesoSolver> solver;
};

std::unique_ptr<Column> build(int n_y, int m, int variant = 0) {
  const bool auto_backend = variant == 1;
  const Registry& reg = builtin_registry();
  auto c = std::make_unique<Column>();
  c->scene = reg.scenes.create(
      reg.scenes.resolve(json{{"name", "poiseuille-uniform"}, {"n_y", n_y}, {"n_x", 12}, {"eta_over_ly", 1.0 / m}},
                         "/scene"),
      "/scene");
  c->kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", c->scene->eta}}, "/kernel");
  c->deconvolver = reg.deconvolvers.create(reg.deconvolvers.resolve(json{{"name", "tikhonov"},
                                                                         {"alpha", 1e-6},
                                                                         {"regularizer", "first_difference_zero_ends"},
                                                                         {"backend", auto_backend ? "auto" : "dual"}},
                                                                    "/deconvolver"),
                                           "/deconvolver");
  c->quadrature = reg.quadratures.create(
      reg.quadratures.resolve(json{{"name", "coarse"}, {"stride_x", 0}, {"stride_y", 4}}, "/quadrature"),
      "/quadrature");
  c->integrator = reg.integrators.create(json{{"name", variant == 2 ? "newton" : "backward_euler"}}, "/integrator");
  MesoSolverOptions opt;
  opt.scheme = MesoScheme::staggered;
  opt.discretization = Discretization::coarse_fine;
  opt.balance = MesoBalance::force_density;
  opt.wall_node_value = WallNodeValue::reconstructed;
  opt.wall_constraint_forces = true;
  opt.to_steady_state = true;
  opt.max_time = 20.0;
  c->solver = std::make_unique<MesoSolver>(*c->scene, *c->kernel, *c->deconvolver, *c->quadrature, *c->integrator, opt);
  return c;
}

void counters(benchmark::State& state, const Column& c) {
  state.counters["rows"] = static_cast<double>(c.scene->ny);
  state.counters["coarse_nodes"] = static_cast<double>(c.solver->coarse_mesh().count);
}

void Reduced1D_NearWallSetup(benchmark::State& state) {
  const int n_y = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  const int variant = static_cast<int>(state.range(2));
  std::unique_ptr<Column> c;
  for (auto _ : state) {
    c = build(n_y, m, variant);
    benchmark::DoNotOptimize(c);
  }
  counters(state, *c);
}

void Reduced1D_NearWallSteady(benchmark::State& state) {
  const int n_y = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  const int variant = static_cast<int>(state.range(2));
  std::unique_ptr<Column> c;
  long steps = 0;
  for (auto _ : state) {
    c = build(n_y, m, variant);
    const MesoResult r = c->solver->run();
    if (r.status != Status::converged) state.SkipWithError("the reduced model did not reach steady state");
    steps = r.steps;
  }
  counters(state, *c);
  state.counters["steps"] = static_cast<double>(steps);
}

void cases(benchmark::internal::Benchmark* b) {
  for (int n_y : {192, 384, 768, 1536}) b->Args({n_y, 16, 0});
  for (int m : {32, 64, 128}) b->Args({1536, m, 0});
  for (int n_y : {192, 1536}) b->Args({n_y, 16, 1});
  for (int n_y : {192, 384, 768, 1536}) b->Args({n_y, 16, 2});
  for (int m : {32, 64, 128}) b->Args({1536, m, 2});
  b->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(Reduced1D_NearWallSetup)->Apply(cases);
BENCHMARK(Reduced1D_NearWallSteady)->Apply(cases);
