// The 2D force-density model with the transport-velocity formulation's pair forces (solver.pair_forces:
// transport_velocity, core/reduced/force_density_2d.hpp) on the small cylinder lattice of test_force_density_2d.cpp
// (n = 32, η' = L/8). Each map against an independent evaluation at the particles:
// - the velocity's response against the direct SPH engine under the transport-velocity formulation with the
//   generalized wall condition (core/sph/sph_engine_transport.cpp: the solids' ghost velocities from their fluid
//   neighbours), the engine's accelerations at a velocity field less those at rest, averaged;
// - the forces at rest (the body force, the walls' hydrostatic pressure, the rest pressure where a wall's volume
//   differs from a fluid particle's) against the engine's accelerations at rest;
// - the pressure's response against the transport-velocity pair terms (core/sph/transport_velocity.hpp) with the
//   walls' extrapolated pressure, summed over all pairs by a plain loop at n = n0 + ε δn, a central difference in ε.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/transport_velocity.hpp"
#include "tests/support/force_density_setup.hpp"

using namespace closurelab;

namespace {

using closurelab::test_support::random_field;

ForceDensity2DOptions transport_options() {
  return closurelab::test_support::force_density_options({{"pair_forces", "transport_velocity"}});
}

// The mass-weighted average (2.9) at the coarse nodes of a per-particle quantity q (zero on the solid).
Eigen::VectorXd averaged(const Scene& scene, const AveragingKernel& kernel, const TensorMesh2D& mesh, ParticleSystem ps,
                         const Eigen::VectorXd& q) {
  for (std::size_t a = 0; a < ps.size(); ++a) {
    ps.vx[a] = ps.fixed[a] ? 0.0 : q[static_cast<Eigen::Index>(a)];
    ps.vy[a] = 0.0;
  }
  return average_particles(ps, scene.box, kernel, mesh, AveragingRequest{}).vx;
}

double max_abs(const Eigen::VectorXd& v) { return v.cwiseAbs().maxCoeff(); }

// The engine's accelerations under the transport-velocity formulation at the particles' velocities (its first
// evaluation: Ṽ = V, so the extra stress vanishes), both components, zero on the solid.
void engine_accelerations(const Scene& scene, ParticleSystem ps, Eigen::VectorXd& ax, Eigen::VectorXd& ay) {
  SphEngineOptions opt;
  opt.formulation = SphFormulation::transport_velocity;
  SphEngine engine(scene, ps, opt);
  engine.compute_accelerations();
  ax = ay = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(ps.size()));
  for (std::int32_t a : engine.moving()) {
    ax[a] = engine.ax()[static_cast<std::size_t>(a)];
    ay[a] = engine.ay()[static_cast<std::size_t>(a)];
  }
}

// m_a × a's acceleration from the pressure terms of the transport-velocity pairs, at number densities n0 + δn (the
// solids' own δn unused: their pressure is the wall condition's), by a loop over all pairs (minimum images).
void pressure_forces(const Scene& scene, const ParticleSystem& ps, double n0, const Eigen::VectorXd& dn,
                     Eigen::VectorXd& fx, Eigen::VectorXd& fy) {
  const SmoothingKernel w = scene.smoothing_kernel();
  const double m = scene.particle_mass(), rho0 = scene.rho0, p0 = rho0 * scene.sound_speed * scene.sound_speed;
  const double eps = 0.01 * w.h() * w.h(), wall_vol2 = std::pow(scene.dx, 4);
  const auto image = [](double d, double l) { return d - l * std::nearbyint(d / l); };
  const std::size_t np = ps.size();
  std::vector<TvfParticle> in(np);
  for (std::size_t a = 0; a < np; ++a) {
    const double n = n0 + dn[static_cast<Eigen::Index>(a)];
    in[a] = tvf_particle(n, m, scene.pressure(n, m), 0.0, 0.0, 0.0, 0.0, 0.0);  // ν = 0: no viscous term
  }
  for (std::size_t wl = 0; wl < np; ++wl) {  // SolidWallPressureBC
    if (!ps.fixed[wl]) continue;
    double sw = 0.0, sp = 0.0;
    for (std::size_t f = 0; f < np; ++f) {
      if (ps.fixed[f]) continue;
      const double qx = image(ps.x[wl] - ps.x[f], scene.box.lx), qy = image(ps.y[wl] - ps.y[f], scene.box.ly);
      const double r = std::hypot(qx, qy);
      if (r >= w.support()) continue;
      const Vec2 g = scene.body_force ? scene.body_force(ps.x[wl], ps.y[wl]) : Vec2(scene.force_x(ps.y[wl]), 0.0);
      sw += w.w(r);
      sp += (in[f].p + in[f].rho * (g.x() * qx + g.y() * qy)) * w.w(r);
    }
    const double p = sw > 0.0 ? sp / sw : 0.0;
    in[wl] = {rho0 * ((p - scene.background_pressure) / p0 + 1.0), p, wall_vol2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  }
  fx = fy = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(np));
  for (std::size_t a = 0; a < np; ++a) {
    if (ps.fixed[a]) continue;
    for (std::size_t b = 0; b < np; ++b) {
      const double qx = image(ps.x[a] - ps.x[b], scene.box.lx), qy = image(ps.y[a] - ps.y[b], scene.box.ly);
      const double r = std::hypot(qx, qy);
      if (b == a || r >= w.support()) continue;
      double px, py, bx, by;
      tvf_pair_force<true>(in[a], in[b], w.dw(r) / r, qx, qy, eps, 0.0, px, py, bx, by, 0.0);
      fx[static_cast<Eigen::Index>(a)] += px;
      fy[static_cast<Eigen::Index>(a)] += py;
    }
  }
}

}  // namespace

TEST(ForceDensityTransport, VelocityResponseIsTheTransportEngineWithGhostVelocitiesAveraged) {
  // g = 1e-8: the walls' hydrostatic pressure, which moves their density and so their viscosity by ~g ε'/c²,
  // is below round-off here; a background pressure, which the velocity's response must not see.
  auto s = closurelab::test_support::cylinder_lattice_setup({{"g", 1e-8}, {"background_pressure_factor", 0.01}});
  ForceDensitySolver2D solver(*s.scene, *s.kernel, *s.dv, *s.dn, transport_options());
  const Eigen::Index nr = solver.reconstruction_mesh().size();
  const Eigen::VectorXd rx = random_field(nr, 2), ry = random_field(nr, 3), zero = Eigen::VectorXd::Zero(nr);
  ParticleSystem ps = s.scene->make_particles();
  const Eigen::VectorXd vx = solver.interpolate_to_particles(rx), vy = solver.interpolate_to_particles(ry);
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) ps.vx[a] = vx[static_cast<Eigen::Index>(a)], ps.vy[a] = vy[static_cast<Eigen::Index>(a)];
  Eigen::VectorXd ax, ay, ax0, ay0;
  engine_accelerations(*s.scene, ps, ax, ay);
  engine_accelerations(*s.scene, s.scene->make_particles(), ax0, ay0);
  const TensorMesh2D& mesh = solver.coarse_mesh();
  const Eigen::VectorXd ref_x = averaged(*s.scene, *s.kernel, mesh, ps, ax - ax0);
  const Eigen::VectorXd ref_y = averaged(*s.scene, *s.kernel, mesh, ps, ay - ay0);
  Eigen::VectorXd mx, my, mn, mx0, my0, mn0;
  solver.rates_from_reconstruction(rx, ry, zero, mx, my, mn);
  solver.rates_from_reconstruction(zero, zero, zero, mx0, my0, mn0);
  EXPECT_LT(max_abs(mx - mx0 - ref_x), 1e-8 * max_abs(ref_x));
  EXPECT_LT(max_abs(my - my0 - ref_y), 1e-8 * max_abs(ref_y));
  // The ghost velocity matters: the standard model's zero-velocity solid differs by much more.
  ForceDensitySolver2D standard(*s.scene, *s.kernel, *s.dv, *s.dn, closurelab::test_support::force_density_options());
  standard.rates_from_reconstruction(rx, ry, zero, mx, my, mn);
  standard.rates_from_reconstruction(zero, zero, zero, mx0, my0, mn0);
  EXPECT_GT(max_abs(mx - mx0 - ref_x), 1e-2 * max_abs(ref_x));
}

namespace {

// The model's forces at rest (its rates at zero data) against the engine's accelerations at rest, averaged: the
// largest difference and the largest difference of the body force's average alone, both over the engine's largest.
std::pair<double, double> forces_at_rest(const json& scene_extra) {
  auto s = closurelab::test_support::cylinder_lattice_setup(scene_extra);
  ForceDensitySolver2D solver(*s.scene, *s.kernel, *s.dv, *s.dn, transport_options());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(solver.reconstruction_mesh().size());
  const ParticleSystem ps = s.scene->make_particles();
  Eigen::VectorXd ax, ay;
  engine_accelerations(*s.scene, ps, ax, ay);
  const TensorMesh2D& mesh = solver.coarse_mesh();
  const Eigen::VectorXd ref_x = averaged(*s.scene, *s.kernel, mesh, ps, ax);
  const Eigen::VectorXd ref_y = averaged(*s.scene, *s.kernel, mesh, ps, ay);
  Eigen::VectorXd mx, my, mn;
  solver.rates_from_reconstruction(zero, zero, zero, mx, my, mn);
  const double scale = std::max(max_abs(ref_x), max_abs(ref_y));
  Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(ps.size()));
  for (std::size_t a = 0; a < ps.size(); ++a) g[static_cast<Eigen::Index>(a)] = s.scene->force_x(ps.y[a]);
  const Eigen::VectorXd g_bar = averaged(*s.scene, *s.kernel, mesh, ps, g);
  const double body_only = std::max(max_abs(g_bar - ref_x), max_abs(ref_y)) / scale;
  std::printf("forces at rest: model %.3e, body force alone %.3e of the engine's %.3e\n",
              std::max(max_abs(mx - ref_x), max_abs(my - ref_y)) / scale, body_only, scale);
  return {std::max(max_abs(mx - ref_x), max_abs(my - ref_y)) / scale, body_only};
}

}  // namespace

TEST(ForceDensityTransport, WallsHydrostaticPressureAtRestIsTheTransportEngines) {
  // g = 0.01, no background pressure (the sound speed ν/L-bound, c = 10): the engine's wall density ρ_w =
  // ρ_rest + p_hydrostatic/c² enters its pair pressure at second order in g, at most ~ g ε'/c² = 3e-6 of the force.
  const auto [model, body_only] = forces_at_rest({{"background_pressure_factor", 0.0}});
  EXPECT_LT(model, 1e-6);      // measured 8.6e-8
  EXPECT_GT(body_only, 1e-2);  // without the walls' pressure the model would be far from the engine
}

TEST(ForceDensityTransport, RestPressureWhereWallVolumesDifferIsTheTransportEngines) {
  // g = 1e-8, P0 = 0.01 ρ0 c²: the force of the rest pressure where a wall's V_w² = ε'⁴ differs from 1/n0², exact.
  const auto [model, body_only] = forces_at_rest({{"g", 1e-8}, {"background_pressure_factor", 0.01}});
  EXPECT_LT(model, 1e-8);
  EXPECT_GT(body_only, 1e-2);
}

TEST(ForceDensityTransport, PressureResponseIsTheTransportPairForceWithTheWallsExtrapolatedPressure) {
  // g = 1e-8: the hydrostatic part of the walls' pressure, ρ_f g · (x_w − x_f), is affine in the state only at
  // g → 0 (its ρ_f carries δn: a term of order g δn, which the linearisation leaves out).
  auto s = closurelab::test_support::cylinder_lattice_setup({{"g", 1e-8}, {"background_pressure_factor", 0.01}});
  const Scene& scene = *s.scene;
  ForceDensitySolver2D solver(scene, *s.kernel, *s.dv, *s.dn, transport_options());
  const Eigen::Index nr = solver.reconstruction_mesh().size();
  const Eigen::VectorXd rn = random_field(nr, 6), zero = Eigen::VectorXd::Zero(nr);
  const Eigen::VectorXd dn = solver.interpolate_to_particles(rn);
  const ParticleSystem ps = scene.make_particles();
  const SmoothingKernel w = scene.smoothing_kernel();
  double n_lattice = w.w(0.0);  // the lattice's summation density, about which the model is linearised
  const int reach = static_cast<int>(std::ceil(w.support() / scene.dx));
  for (int dj = -reach; dj <= reach; ++dj)
    for (int di = -reach; di <= reach; ++di) {
      const double r = std::hypot(di, dj) * scene.dx;
      if ((di != 0 || dj != 0) && r < w.support()) n_lattice += w.w(r);
    }
  const double eps = 1e-4 * n_lattice;
  Eigen::VectorXd fxp, fyp, fxm, fym;
  pressure_forces(scene, ps, n_lattice, eps * dn, fxp, fyp);
  pressure_forces(scene, ps, n_lattice, -eps * dn, fxm, fym);
  const double m = scene.particle_mass();
  const Eigen::VectorXd dfx = (fxp - fxm) / (2.0 * eps * m), dfy = (fyp - fym) / (2.0 * eps * m);
  const TensorMesh2D& mesh = solver.coarse_mesh();
  const Eigen::VectorXd ref_x = averaged(scene, *s.kernel, mesh, ps, dfx);
  const Eigen::VectorXd ref_y = averaged(scene, *s.kernel, mesh, ps, dfy);
  Eigen::VectorXd mx, my, mn, mx0, my0, mn0;
  solver.rates_from_reconstruction(zero, zero, rn, mx, my, mn);
  solver.rates_from_reconstruction(zero, zero, zero, mx0, my0, mn0);
  EXPECT_LT(max_abs(mx - mx0 - ref_x), 1e-6 * max_abs(ref_x));  // O(ε²) of the difference
  EXPECT_LT(max_abs(my - my0 - ref_y), 1e-6 * max_abs(ref_y));
}

TEST(ForceDensityTransport, MovingWallsAreRefusedNamingThePath) {
  auto s = closurelab::test_support::cylinder_lattice_setup();
  Scene scene = *s.scene;
  scene.solid_velocity = [](double, double) { return Vec2(1.0, 0.0); };
  try {
    ForceDensitySolver2D solver(scene, *s.kernel, *s.dv, *s.dn, transport_options());
    FAIL() << "a moving solid was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.path(), "/scene");
  }
}
