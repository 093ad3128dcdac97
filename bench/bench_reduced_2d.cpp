// Micro-benchmarks of the two-dimensional reduced model (core/reduced/meso_solver_2d.hpp).
//
// Reduced2D_Setup / Reduced2D_Step: the linear model on the cellular flow (η' = L/16): its setup (the Kronecker
// operator and the deconvolver's factorization, both face meshes' coarse quadrature tables, the averaged force) and
// one explicit step (two deconvolutions, two quadrature evaluations, the flux differences), as the lattice N = n²
// and the coarse mesh N_C = m² grow. Arguments (n, m): the coarse spacing is L/m, the coarse quadrature's R-grid
// stride is n/m lattice spacings (the coarse spacing, so its table does not grow with n), the closure is CGLS
// (10 iterations) on the coarse–fine operator.
//
// Reduced2D_TaylorGreenSetup / Reduced2D_TaylorGreenStep: the nonlinear model stepped in time (solver.equations
// incompressible: the convective flux of the closure's velocities, the discrete projection) on the Taylor–Green
// vortex at Re = 100 (h = 1.5 ε'), the paper's Landweber order 2 on the coarse–coarse operator, as in
// experiments/taylor_green/reduced_2d_re100.json. Arguments (n, m, table): table = 1 forces the coarse quadrature's
// bond-weight table, 0 lets it convolve by FFT (one R-cell per face node: strategies/quadrature/coarse_quadrature.hpp).
// At fixed m the work of a step does not depend on n (N_C J pair forces, J the SPH support's lattice offsets).
// Run:
//   OMP_NUM_THREADS=1 build/bench/closurelab_bench --benchmark_filter=Reduced2D
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "core/base/registry.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/sph/scene.hpp"
#include "strategies/quadrature/coarse_quadrature.hpp"

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

std::unique_ptr<Model> build_taylor_green(int n, int m, bool table) {
  const Registry& reg = builtin_registry();
  auto model = std::make_unique<Model>();
  model->scene = reg.scenes.create(
      json{{"name", "taylor-green"}, {"re", 100}, {"n", n}, {"eta_over_l", 1.0 / 16}, {"h_over_dx", 1.5}}, "/scene");
  model->kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", model->scene->eta}}, "/kernel");
  model->deconvolver = reg.deconvolvers.create(json{{"name", "landweber"}, {"order", 2}}, "/deconvolver");
  model->on_x = std::make_unique<CoarseQuadrature>(n / m, n / m, false, !table);
  model->on_y = std::make_unique<CoarseQuadrature>(n / m, n / m, false, !table);
  model->integrator = reg.integrators.create(json{{"name", "explicit"}}, "/integrator");
  MesoSolver2DOptions opt;
  opt.spacing_over_eta = 16.0 / m;
  opt.equations = CoarseEquations::incompressible;
  model->solver = std::make_unique<MesoSolver2D>(*model->scene, *model->kernel, *model->deconvolver, *model->on_x,
                                                 *model->on_y, *model->integrator, opt);
  // The vortex's velocity at the coarse nodes (its amplitude sets the step).
  const TensorMesh2D& mesh = model->solver->coarse_mesh();
  Eigen::VectorXd vx(mesh.size()), vy(mesh.size());
  for (int k = 0; k < mesh.size(); ++k) {
    const Vec2 q = mesh.node(k) * (2.0 * M_PI);
    vx[k] = std::sin(q.x()) * std::cos(q.y());
    vy[k] = -std::cos(q.x()) * std::sin(q.y());
  }
  model->solver->set_velocity(vx, vy);
  return model;
}

void counters(benchmark::State& state, const Model& model, int n, int m) {
  state.counters["particles"] = static_cast<double>(n) * n;
  state.counters["coarse_nodes"] = static_cast<double>(m) * m;
  state.counters["bond_weights"] =
      static_cast<double>(model.on_x->setup_cost().bond_weights + model.on_y->setup_cost().bond_weights);
  state.counters["sample_points"] =
      static_cast<double>(model.on_x->setup_cost().sample_points + model.on_y->setup_cost().sample_points);
}

void Reduced2D_TaylorGreenSetup(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  std::unique_ptr<Model> model;
  for (auto _ : state) {
    model = build_taylor_green(n, m, state.range(2) != 0);
    benchmark::DoNotOptimize(model);
  }
  counters(state, *model, n, m);
}

void Reduced2D_TaylorGreenStep(benchmark::State& state) {
  static std::map<std::array<int, 3>, std::unique_ptr<Model>> models;  // set up once per case
  const int n = static_cast<int>(state.range(0)), m = static_cast<int>(state.range(1));
  auto& model = models[{n, m, static_cast<int>(state.range(2))}];
  if (!model) model = build_taylor_green(n, m, state.range(2) != 0);
  MesoSolver2D& solver = *model->solver;
  const double dt = solver.time_step();
  std::string issue;
  for (auto _ : state)
    if (!solver.step(dt, issue)) state.SkipWithError(issue.c_str());
  counters(state, *model, n, m);
}

// N at fixed N_C = 16² (n = 64 to 512), the table against the convolution at n = 128, and N_C = 32², 64² at
// n = 256. A step samples the closure at the virtual pairs' ends, at most N_C (J + 1) distinct points; at small
// strides neighbouring R-cells share ends, so below n = 256 (stride 16) there are fewer (8450 at n = 64, 30528 at
// 128, 35328 from 256 on, both face meshes): the step is cheaper there, and flat from the stride where none coincide.
void taylor_green_cases(benchmark::internal::Benchmark* b) {
  for (const int n : {64, 128, 256, 512}) b->Args({n, 16, 0});
  b->Args({128, 16, 1});
  b->Args({256, 32, 0});
  b->Args({256, 64, 0});
  b->Unit(benchmark::kMillisecond);
}
BENCHMARK(Reduced2D_TaylorGreenSetup)->Apply(taylor_green_cases);
BENCHMARK(Reduced2D_TaylorGreenStep)->Apply(taylor_green_cases);

}  // namespace
