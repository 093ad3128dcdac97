// Micro-benchmarks of the two-dimensional reduced model (core/reduced/meso_solver_2d.hpp) on the cellular flow
// (η' = L/16): its setup (the Kronecker operator and the deconvolver's factorization, both face meshes' coarse
// quadrature tables, the averaged force) and one explicit step (two deconvolutions, two quadrature evaluations,
// the flux differences), as the lattice N = n² and the coarse mesh N_C = m² grow. Arguments (n, m): the coarse
// spacing is L/m, the coarse quadrature's R-grid stride is n/m lattice spacings (the coarse spacing, so its table
// does not grow with n), the closure is CGLS (10 iterations) on the coarse–fine operator. Run:
//   OMP_NUM_THREADS=1 build/bench/closurelab_bench --benchmark_filter=Reduced2D
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <utility>

#include "core/base/registry.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/sph/scene.hpp"

using namespace closurelab;

namespace {

struct Model {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<AveragingKernel> kernel;
  std::unique_ptr<Deconvolver> deconvolver;
  std::unique_ptr<StressQuadrature> on_x, on_y;
  std::unique_ptr<Integrator> integrator;
  std::unique_ptr<MesoSolver2D> solver;
};

std::unique_ptr<Model> build(int n, int m) {
  const Registry& reg = builtin_registry();
  auto model = std::make_unique<Model>();
  model->scene = reg.scenes.create(json{{"name", "cellular"}, {"n", n}, {"eta_over_l", 1.0 / 16}}, "/scene");
  model->kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", model->scene->eta}}, "/kernel");
  model->deconvolver = reg.deconvolvers.create(json{{"name", "cgls"}, {"iterations", 10}}, "/deconvolver");
  const json q = {{"name", "coarse"}, {"stride_x", n / m}, {"stride_y", n / m}};
  model->on_x = reg.quadratures.create(q, "/quadrature");
  model->on_y = reg.quadratures.create(q, "/quadrature");
  model->integrator = reg.integrators.create(json{{"name", "explicit"}}, "/integrator");
  MesoSolver2DOptions opt;
  opt.spacing_over_eta = 16.0 / m;
  opt.discretization = Discretization::coarse_fine;
  model->solver = std::make_unique<MesoSolver2D>(*model->scene, *model->kernel, *model->deconvolver, *model->on_x,
                                                 *model->on_y, *model->integrator, opt);
  return model;
}

void Reduced2D_Setup(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  long weights = 0;
  for (auto _ : state) {
    auto model = build(n, m);
    weights = model->on_x->setup_cost().bond_weights + model->on_y->setup_cost().bond_weights;
    benchmark::DoNotOptimize(model);
  }
  state.counters["particles"] = static_cast<double>(n) * n;
  state.counters["coarse_nodes"] = static_cast<double>(m) * m;
  state.counters["bond_weights"] = static_cast<double>(weights);
}
BENCHMARK(Reduced2D_Setup)->Args({48, 16})->Args({96, 16})->Args({192, 16})->Args({192, 32})->Unit(benchmark::kMillisecond);

void Reduced2D_Step(benchmark::State& state) {
  static std::map<std::pair<int, int>, std::unique_ptr<Model>> models;  // set up once per size
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  auto& model = models[{n, m}];
  if (!model) model = build(n, m);
  MesoSolver2D& solver = *model->solver;
  const double dt = solver.time_step();
  std::string issue;
  for (auto _ : state)
    if (!solver.step(dt, issue)) state.SkipWithError(issue.c_str());
  state.counters["particles"] = static_cast<double>(n) * n;
  state.counters["coarse_nodes"] = static_cast<double>(m) * m;
}
BENCHMARK(Reduced2D_Step)->Args({48, 16})->Args({96, 16})->Args({192, 16})->Args({192, 32})->Unit(benchmark::kMillisecond);

}  // namespace
