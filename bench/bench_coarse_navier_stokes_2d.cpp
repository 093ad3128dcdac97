// Micro-benchmark of the coarse continuum baseline (core/continuum/coarse_navier_stokes_2d.hpp): one AB2 step with
// its FFT projection (two forward and two inverse 2D transforms, 1D transforms by Eigen's kissfft backend) on the
// Taylor–Green vortex at Re = 100 (L = U = 1), against the mesh m × m = 16² … 64² (N_C = m²; the cost should grow
// as N_C log N_C). The state is set once per size and stepped on (it decays slowly; the step's cost does not depend
// on it). Run:
//   OMP_NUM_THREADS=1 build/bench/closurelab_bench --benchmark_filter=CoarseNavierStokes2D
#include <benchmark/benchmark.h>

#include <cmath>

#include "core/continuum/coarse_navier_stokes_2d.hpp"

using namespace closurelab;

namespace {

void CoarseNavierStokes2D_Step(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const TensorMesh2D mesh{UniformMesh1D::cell_centred(0.0, 1.0, m, true),
                          UniformMesh1D::cell_centred(0.0, 1.0, m, true)};
  CoarseNavierStokes2D ns(mesh, 1.0, 0.01, {}, {});
  Eigen::VectorXd vx(mesh.size()), vy(mesh.size());
  const double k = 2.0 * M_PI;
  for (int n = 0; n < mesh.size(); ++n) {
    const Vec2 q = mesh.node(n);
    vx[n] = -std::cos(k * q.x()) * std::sin(k * q.y());
    vy[n] = std::sin(k * q.x()) * std::cos(k * q.y());
  }
  ns.set_velocity(vx, vy);
  const double dt = ns.time_step();
  for (auto _ : state)
    if (!ns.step(dt)) state.SkipWithError("non-finite state");
  state.counters["coarse_nodes"] = static_cast<double>(m) * m;
}
BENCHMARK(CoarseNavierStokes2D_Step)->Arg(16)->Arg(24)->Arg(32)->Arg(48)->Arg(64)->Unit(benchmark::kMicrosecond);

}  // namespace
