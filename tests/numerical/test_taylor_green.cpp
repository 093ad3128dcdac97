// The Taylor–Green vortex at Re = 100 (scene "taylor-green", PySPH's taylor_green.py) under the transport-velocity
// formulation (solver.formulation transport_velocity): the largest particle speed against the exact decay
// U e^{−8π²t/Re}, as PySPH's post-processing measures it (|max|v| − U e^{bt}| / (U e^{bt})), and against the same
// history computed by PySPH 1.0b1's own TVF scheme at n = 25: to round-off when both start with ṽ = v, to 0.055 %
// against PySPH's unmodified example.
//
// What was measured (this engine, one thread; the max|v| error against the exact decay):
//   n = 25:  0.90 % at t = 0.05, 3.0 % at t = 0.1, 11.5 % at 0.15, 21 % at 0.2, 20–31 % up to t = 1;
//   n = 50:  0.16 % at t = 0.1, 16 % at 0.2, 38–43 % from t = 0.4 to 2;  n = 100: 0.68 % at 0.1, 8 % at 0.2, 19–21 %
//   from t = 1 to 2 (experiments/taylor_green/tvf_re100.json). The early error falls with n; the later, a loss of
//   the largest speed within t ≈ 0.1–0.4, does not fall from 25 to 50. PySPH's TVF shows the same loss (below), so
//   it is the formulation as PySPH sets this flow up (the summation density cannot start from the exact pressure),
//   not this engine: the 1 % target is not met by it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"

using namespace closurelab;

namespace {

struct History {
  std::vector<double> times, speed, error;  // max|v| and its relative error against U e^{bt}
  std::vector<double> field_error;          // ‖v − v_exact‖₂ / ‖v_exact‖₂ over the particles
};

History run(int n, double end, double every, double perturbation = 0.0) {
  const auto scene = builtin_registry().scenes.create(
      {{"name", "taylor-green"}, {"n", n}, {"perturbation", perturbation}}, "/scene");
  const Scene::TaylorGreenVortex tg = scene->taylor_green.value();
  ParticleSystem ps = scene->make_particles();
  SphRunOptions opt;
  opt.to_steady_state = false;
  opt.target_time = end;
  opt.engine.formulation = SphFormulation::transport_velocity;
  const int count = static_cast<int>(std::lround(end / every));
  for (int k = 1; k <= count; ++k) opt.snapshot_times.push_back(end * k / count);
  History h;
  opt.on_snapshot = [&](double t, const ParticleSystem& now) {
    double v2 = 0.0, d2 = 0.0, e2 = 0.0;
    for (std::size_t a = 0; a < now.size(); ++a) {
      v2 = std::max(v2, now.vx[a] * now.vx[a] + now.vy[a] * now.vy[a]);
      const Vec2 e = tg.velocity_at(now.x[a], now.y[a], t);
      d2 += (now.vx[a] - e.x()) * (now.vx[a] - e.x()) + (now.vy[a] - e.y()) * (now.vy[a] - e.y());
      e2 += e.x() * e.x() + e.y() * e.y();
    }
    h.field_error.push_back(std::sqrt(d2 / e2));
    const double exact = tg.max_speed(t);
    h.times.push_back(t);
    h.speed.push_back(std::sqrt(v2));
    h.error.push_back(std::abs(std::sqrt(v2) - exact) / exact);
  };
  const SphRunResult r = run_direct_sph(*scene, ps, opt);
  EXPECT_EQ(r.status, Status::target_time);
  std::cout << "n = " << n << ": " << r.steps << " steps, dt = " << r.dt << ", " << r.wall_seconds << " s\n";
  for (std::size_t k = 0; k < h.times.size(); ++k)
    std::cout << "  t = " << h.times[k] << ": max|v| = " << h.speed[k] << ", error " << h.error[k]
              << ", field error " << h.field_error[k] << "\n";
  return h;
}

}  // namespace

// At t = 0.1 (one tenth of the unit L/U, 110 and 220 steps) the error falls from 3.0 % (n = 25) to 0.16 % (n = 50),
// measured. Tolerances: 2x the n = 25 figure and 3x the n = 50 one (a formulation whose early error does not fall
// with n fails the second, and so does a decay rate off by half: 8π²t/Re is 7.9 % at t = 0.1).
TEST(TaylorGreenTransportVelocity, EarlyMaxVelocityErrorFallsWithN) {
  const History coarse = run(25, 0.1, 0.05), fine = run(50, 0.1, 0.05);
  ASSERT_EQ(coarse.error.size(), 2u);
  ASSERT_EQ(fine.error.size(), 2u);
  EXPECT_LT(coarse.error.back(), 0.06);
  EXPECT_LT(fine.error.back(), 0.005);
  EXPECT_LT(fine.error.back(), coarse.error.back());
}

// PySPH 1.0b1's TVF on the same scene (n = 25, Re = 100, dt = 0.25 h/(c0 + U)), from
//   /usr/bin/python3 /usr/lib/python3/dist-packages/pysph/examples/taylor_green.py --nx 25 --tf 1.0 --pfreq 55 -d DIR
// and max(sqrt(u² + v²)) over the fluid of each output file (pysph.solver.utils.load), t = 0.05, 0.1, ..., 0.5.
// Its first evaluation has uhat = 0 (this engine's ṽ = v, transport_velocity.hpp), so the two differ by more than
// round-off; measured: at most 0.055 % relative over these times (0.6 % by t = 1, the particles' disorder amplifying
// the start's difference). Tolerance 0.3 % (5x): the 21 % dip at t = 0.2 must be reproduced. (Not yet shown: which
// planted change of a TVF term this fails on; the round-off peer comparison to come is the test for that.)
TEST(TaylorGreenTransportVelocity, MaxVelocityHistoryMatchesPySphsTvf) {
  const double pysph[10] = {0.9522720, 0.9513001, 0.7860187, 1.034474, 0.7458653,
                            0.6666726, 0.6086834, 0.5677546, 0.5439523, 0.5151220};
  const History h = run(25, 0.5, 0.05);
  ASSERT_EQ(h.speed.size(), 10u);
  for (std::size_t k = 0; k < 10; ++k) EXPECT_NEAR(h.speed[k] / pysph[k], 1.0, 3e-3) << "t = " << h.times[k];
}

// PySPH 1.0b1's TVF started as this engine starts (uhat = u at t = 0), from
//   /usr/bin/python3 scripts/peer_taylor_green.py --nx 25 --tf 0.2 --pfreq 55 -d DIR
// (max|v| at t = 0.05, 0.1, 0.15: 55, 110, 165 steps of the same fixed dt). Measured against this engine: 1.5e-15,
// 1.7e-15 and 6.6e-15 relative, i.e. the same equations to round-off (PySPH sums each particle's neighbours in
// another order). Tolerance 1e-12. For scale, the one change of the first evaluation's extra stress that PySPH's
// unmodified example makes (uhat = 0: A = −ρ v ⊗ v once) moves max|v| at t = 0.05 by 4.3e-4 (0.9522720 above).
// Later snapshots are left out: this engine's time loop shortens a step to land on a snapshot time and sometimes
// adds one (1103 steps to t = 1 against PySPH's 1100), and the step after it predicts with that evaluation's
// acceleration (PEC), so the two part by 6e-5 at t = 0.2.
TEST(TaylorGreenTransportVelocity, EqualsPySphsTvfToRoundOffWhenStartedAlike) {
  const double pysph[3] = {9.5267902109525870e-01, 9.5179022362047383e-01, 7.8634786648424482e-01};
  const History h = run(25, 0.15, 0.05);
  ASSERT_EQ(h.speed.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    std::cout.precision(17);
    std::cout << "t = " << h.times[k] << ": this engine " << h.speed[k] << ", PySPH " << pysph[k] << ", relative "
              << h.speed[k] / pysph[k] - 1.0 << "\n";
    EXPECT_NEAR(h.speed[k] / pysph[k], 1.0, 1e-12) << "t = " << h.times[k];
  }
}

// The lattice start's loss is the lattice's: the flow's saddle points (L/4, L/4), ... strain the square lattice
// (spacing × e^{±2πUt/L}, 1.9 and 0.53 by t = 0.1), which the summation density reads as a pressure error
// c² δn/n several times the flow's ½ρU², and the background pressure does not undo a uniformly strained lattice
// (Σ_b ∇W_ab vanishes on any lattice). Started off the lattice (`perturbation`, PySPH's --perturb: each particle
// shifted by U[0, 0.3) ε' along x and y), the particles stay disordered and the field follows the exact one.
// Measured (n = 25, the particles' velocity against the exact field, relative L2, at t = 0.4) with PySPH 1.0b1
// (its taylor_green.py with uhat = u at t = 0, --nx 25 --tf 0.5 --pfreq 55 [--perturb 0.3]): 0.411 on the lattice,
// 0.138 perturbed; this engine: 0.411 and 0.139 (max|v| 22.1 % low and 8.6 % high). Bounds: the lattice above 0.3 (the old start violates the
// perturbed start's bound by 2x), the perturbed below 0.2 (1.4x its figure).
TEST(TaylorGreenTransportVelocity, PerturbedStartKeepsTheFieldThatTheLatticeStartLoses) {
  const History lattice = run(25, 0.4, 0.2), perturbed = run(25, 0.4, 0.2, 0.3);
  ASSERT_EQ(lattice.field_error.size(), 2u);
  ASSERT_EQ(perturbed.field_error.size(), 2u);
  EXPECT_GT(lattice.field_error.back(), 0.3);
  EXPECT_LT(perturbed.field_error.back(), 0.2);
}
