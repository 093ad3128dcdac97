// The 2D reduced model in a walled box (core/reduced/walled_box_2d.hpp, the lid-driven cavity), each piece against
// an independent check:
//   - the walled face difference is exact on linear fields and converges at orders 2 and 4 inside;
//   - the walled projection leaves no discrete divergence, is idempotent and orthogonal;
//   - the fluid's part of the average: the engine's average (2.9) of the particles (fluid carrying a smooth field,
//     walls their prescribed velocity) turned into fluid data equals the Kronecker operator on the fluid lattice;
//   - the walls' constraint forces close the fluid's averaged balance: Σ_fluid ψ F_f = div T_int + F_c at every node,
//     div T_int by central differences of the exact quadrature (2.13) at shifted nodes;
//   - the model in the cavity, started at rest (the lid's share of the average in place): the lid drags the top row
//     along +x, the discrete divergence keeps its initial value.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/registry.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "core/continuum/continuum_navier_stokes_2d.hpp"
#include "core/reduced/integrator.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/reduced/walled_box_2d.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_engine.hpp"

using namespace closurelab;

namespace {

struct Cavity {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<AveragingKernel> kernel;
  TensorMesh2D coarse;
};

// n = 24 particles per side, η' = L/8: an 8 x 8 coarse mesh over the fluid's square.
Cavity make_cavity(int n = 24) {
  const Registry& reg = builtin_registry();
  Cavity c;
  c.scene =
      reg.scenes.create(json{{"name", "lid-driven-cavity"}, {"n", n}, {"eta_over_l", 0.125}, {"re", 100}}, "/scene");
  c.kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", c.scene->eta}}, "/kernel");
  c.coarse = continuum_mesh_for(*c.scene, *c.kernel, 1.0);
  return c;
}

Vec2 smooth_field(double x, double y) {
  return {std::sin(3.0 * x + 0.4) * std::cos(2.0 * y), 0.5 * std::cos(x - 2.0 * y)};
}

TensorMesh2D square_cells(int n) {
  const UniformMesh1D a = UniformMesh1D::cell_centred(0.0, 1.0, n, false);
  return {a, a};
}

}  // namespace

TEST(ReducedModel2DWalls, FaceDifferenceIsExactOnLinesAndConvergesAtItsOrder) {
  const auto error = [](int n, int order) {
    const TensorMesh2D cells = square_cells(n), faces = walled_faces_of(cells, 0);
    Eigen::VectorXd f(faces.size()), lin(faces.size());
    for (int k = 0; k < faces.size(); ++k) {
      f[k] = std::sin(2.0 * faces.node(k).x()) * faces.node(k).y();
      lin[k] = 3.0 * faces.node(k).x() - faces.node(k).y();
    }
    const Eigen::VectorXd d = walled_face_difference(cells, f, 0, order),
                          dl = walled_face_difference(cells, lin, 0, order);
    double e = 0.0;
    for (int k = 0; k < cells.size(); ++k) {
      EXPECT_NEAR(dl[k], 3.0, 1e-11);
      const Vec2 p = cells.node(k);
      if (p.x() > 0.2 && p.x() < 0.8) e = std::max(e, std::abs(d[k] - 2.0 * std::cos(2.0 * p.x()) * p.y()));
    }
    return e;
  };
  EXPECT_NEAR(std::log2(error(16, 2) / error(32, 2)), 2.0, 0.05);
  EXPECT_NEAR(std::log2(error(16, 4) / error(32, 4)), 4.0, 0.15);
}

TEST(ReducedModel2DWalls, ProjectionLeavesNoDivergenceAndIsAnOrthogonalProjection) {
  for (int order : {2, 4}) {
    const TensorMesh2D cells = square_cells(12);
    const WalledProjection2D p(cells, order);
    Eigen::VectorXd ux = Eigen::VectorXd::Random(cells.size()), uy = Eigen::VectorXd::Random(cells.size());
    Eigen::VectorXd vx = ux, vy = uy;
    p.project(vx, vy);
    EXPECT_LT(p.divergence(vx, vy).cwiseAbs().maxCoeff(), 1e-10 * p.divergence(ux, uy).cwiseAbs().maxCoeff());
    Eigen::VectorXd wx = vx, wy = vy;
    p.project(wx, wy);
    EXPECT_LT(std::max((wx - vx).cwiseAbs().maxCoeff(), (wy - vy).cwiseAbs().maxCoeff()), 1e-12);
    // ⟨Π u, u − Π u⟩ = 0
    EXPECT_NEAR(vx.dot(ux - vx) + vy.dot(uy - vy), 0.0, 1e-10 * (ux.squaredNorm() + uy.squaredNorm()));
  }
  EXPECT_THROW(WalledProjection2D(square_cells(kMaxWalledProjectionSide + 1), 2), ConfigError);
}

TEST(ReducedModel2DWalls, FluidDataOfTheAverageIsTheKroneckerOperatorOnTheFluidLattice) {
  const Cavity c = make_cavity();
  ParticleSystem ps = c.scene->make_particles();
  const WalledAveraging w = walled_averaging(*c.scene, *c.kernel, c.coarse);
  const TensorMesh2D& lattice = w.fluid_lattice;
  ASSERT_EQ(lattice.size(), 24 * 24);
  Eigen::VectorXd ux(lattice.size()), uy(lattice.size());
  for (int k = 0; k < lattice.size(); ++k) {
    const Vec2 u = smooth_field(lattice.node(k).x(), lattice.node(k).y());
    ux[k] = u.x();
    uy[k] = u.y();
  }
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) {
      const Vec2 u = smooth_field(ps.x[a], ps.y[a]);
      ps.vx[a] = u.x();
      ps.vy[a] = u.y();
    }
  const MesoFields f = average_particles(ps, c.scene->box, *c.kernel, c.coarse, AveragingRequest{});
  const ForwardOperator a = make_averaging_operator_2d(*c.kernel, c.coarse, lattice, Discretization::coarse_fine);
  EXPECT_LT((w.fluid_data(f.vx, 0) - a.apply(ux)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT((w.fluid_data(f.vy, 1) - a.apply(uy)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_GT(w.wall_x.maxCoeff(), 1e-3);  // the lid's part near the top
  EXPECT_EQ(w.wall_y.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ReducedModel2DWalls, ConstraintForcesCloseTheFluidsAveragedBalance) {
  const Cavity c = make_cavity();
  const Registry& reg = builtin_registry();
  const VelocitySampler field = [](const std::vector<Vec2>& pts) {
    Eigen::Matrix2Xd v(2, static_cast<Eigen::Index>(pts.size()));
    for (std::size_t k = 0; k < pts.size(); ++k)
      v.col(static_cast<Eigen::Index>(k)) = smooth_field(pts[k].x(), pts[k].y());
    return v;
  };
  // Σ_fluid ψ(x_i − q_f) F_f, F_f the fluid particle's pair forces: the left-hand side, from the pair list alone.
  ParticleSystem ps = c.scene->make_particles();
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a]) {
      const Vec2 u = smooth_field(ps.x[a], ps.y[a]);
      ps.vx[a] = u.x();
      ps.vy[a] = u.y();
    }
  SphEngine engine(*c.scene, ps);
  std::vector<Vec2> force(ps.size(), Vec2(0.0, 0.0));
  for (const PairForce& p : engine.pair_forces()) {
    force[p.j] += p.f;
    force[p.k] -= p.f;
  }
  Eigen::VectorXd lhs_x = Eigen::VectorXd::Zero(c.coarse.size()), lhs_y = lhs_x;
  for (std::size_t a = 0; a < ps.size(); ++a)
    if (!ps.fixed[a])
      for (int i = 0; i < c.coarse.size(); ++i) {
        const double psi = c.kernel->value(c.coarse.node(i) - Vec2(ps.x[a], ps.y[a]));
        lhs_x[i] += psi * force[a].x();
        lhs_y[i] += psi * force[a].y();
      }
  // div T_int by central differences of the exact quadrature at nodes shifted by ±δ.
  const double delta = 1e-4 * c.scene->eta;
  const auto stress_at = [&](double sx, double sy) {
    TensorMesh2D m = c.coarse;
    m.x.origin += sx;
    m.y.origin += sy;
    auto q = reg.quadratures.create(json{{"name", "exact"}}, "/quadrature");
    q->setup(*c.scene, *c.kernel, m, {"xx", "xy", "yx", "yy"});
    return q->evaluate(field).stress;
  };
  const auto xp = stress_at(delta, 0), xm = stress_at(-delta, 0), yp = stress_at(0, delta), ym = stress_at(0, -delta);
  const Eigen::VectorXd div_x = (xp.at("xx") - xm.at("xx") + yp.at("xy") - ym.at("xy")) / (2.0 * delta);
  const Eigen::VectorXd div_y = (xp.at("yx") - xm.at("yx") + yp.at("yy") - ym.at("yy")) / (2.0 * delta);
  WallConstraintForces2D walls(*c.scene, *c.kernel, c.coarse);
  Eigen::VectorXd fcx, fcy;
  std::string issue;
  ASSERT_TRUE(walls.evaluate(field, fcx, fcy, issue)) << issue;
  const double scale = std::max(lhs_x.cwiseAbs().maxCoeff(), lhs_y.cwiseAbs().maxCoeff());
  EXPECT_GT(fcx.cwiseAbs().maxCoeff(), 0.1 * scale);  // the walls matter next to them
  EXPECT_LT((div_x + fcx - lhs_x).cwiseAbs().maxCoeff(), 1e-5 * scale);
  EXPECT_LT((div_y + fcy - lhs_y).cwiseAbs().maxCoeff(), 1e-5 * scale);
  // Without F_c the balance fails next to the walls.
  EXPECT_GT((div_x - lhs_x).cwiseAbs().maxCoeff(), 0.1 * scale);
}

TEST(ReducedModel2DWalls, TheLidDragsTheTopRowAndTheDivergenceKeepsItsInitialValue) {
  const Cavity c = make_cavity();
  const Registry& reg = builtin_registry();
  MesoSolver2DOptions o;
  o.equations = CoarseEquations::incompressible;
  o.discretization = Discretization::coarse_fine;
  auto deconv = reg.deconvolvers.create(json{{"name", "cgls"}, {"iterations", 10}}, "/deconvolver");
  auto qx = reg.quadratures.create(json{{"name", "exact"}}, "/quadrature");
  auto qy = reg.quadratures.create(json{{"name", "exact"}}, "/quadrature");
  auto integrator = reg.integrators.create(json{{"name", "explicit"}}, "/integrator");
  MesoSolver2D solver(*c.scene, *c.kernel, *deconv, *qx, *qy, *integrator, o);
  const TensorMesh2D& m = solver.coarse_mesh();
  // At rest: the average of the particles, the lid's included (not zero next to the lid).
  const MesoFields rest = average_particles(c.scene->make_particles(), c.scene->box, *c.kernel, m, AveragingRequest{});
  solver.set_velocity(rest.vx, rest.vy);
  const int top = m.index(m.nx() / 2, m.ny() - 1), bottom = m.index(m.nx() / 2, 0);
  const double lid_share = rest.vx[top];
  EXPECT_GT(lid_share, 0.05);
  const WalledProjection2D p(m, o.divergence_order);
  const Eigen::VectorXd d0 = p.divergence(rest.vx, rest.vy);
  EXPECT_GT(d0.cwiseAbs().maxCoeff(), 1e-3);  // the lid's share crosses the side walls' faces near its corners
  std::string issue;
  for (int s = 0; s < 20; ++s) ASSERT_TRUE(solver.step(solver.time_step(), issue)) << issue;
  EXPECT_GT(solver.vx()[top], lid_share + 0.05);  // the lid drags the fluid under it
  EXPECT_LT(std::abs(solver.vx()[bottom]), 0.5 * (solver.vx()[top] - lid_share));
  // The rates are projected: the discrete divergence keeps its initial value.
  EXPECT_LT((p.divergence(solver.vx(), solver.vy()) - d0).cwiseAbs().maxCoeff(), 1e-9);
  // Refused: a walled box under another discretization or other equations.
  o.discretization = Discretization::coarse_coarse;
  EXPECT_THROW(MesoSolver2D(*c.scene, *c.kernel, *deconv, *qx, *qy, *integrator, o), ConfigError);
}

// The fluid's convective flux against the rate of its averaged momentum when its particles move: each fluid particle
// carried along its own velocity V (walls fixed), d/dt Σ_fluid m ψ(x − q_f) V_f = −div Q at every node, the rate by
// a central difference in time of the moved particles' average, div Q by central differences of Q at nodes shifted
// by ±δ (Q as FluidConvectiveFlux forms it: ρ0 times the lattice-to-point Kronecker operator on V ⊗ V).
TEST(ReducedModel2DWalls, ConvectiveFluxIsTheRateOfTheFluidsAveragedMomentum) {
  const Cavity c = make_cavity();
  const TensorMesh2D& lattice = walled_averaging(*c.scene, *c.kernel, c.coarse).fluid_lattice;
  Eigen::VectorXd vx(lattice.size()), vy(lattice.size());
  for (int k = 0; k < lattice.size(); ++k) {
    const Vec2 u = smooth_field(lattice.node(k).x(), lattice.node(k).y());
    vx[k] = u.x();
    vy[k] = u.y();
  }
  const double rho0 = c.scene->rho0, m = c.scene->particle_mass(), dt = 1e-5;
  // Σ_fluid m ψ V at the nodes with every fluid particle moved by τ V.
  const auto momentum = [&](double tau) {
    Eigen::VectorXd px = Eigen::VectorXd::Zero(c.coarse.size()), py = px;
    for (int k = 0; k < lattice.size(); ++k) {
      const Vec2 q = lattice.node(k) + tau * Vec2(vx[k], vy[k]);
      for (int i = 0; i < c.coarse.size(); ++i) {
        const double w = m * c.kernel->value(c.coarse.node(i) - q);
        px[i] += w * vx[k];
        py[i] += w * vy[k];
      }
    }
    return std::make_pair(px, py);
  };
  const auto [pxp, pyp] = momentum(dt);
  const auto [pxm, pym] = momentum(-dt);
  const Eigen::VectorXd rate_x = (pxp - pxm) / (2.0 * dt), rate_y = (pyp - pym) / (2.0 * dt);
  const double delta = 1e-4 * c.scene->eta;
  const auto flux_at = [&](double sx, double sy) {
    TensorMesh2D nodes = c.coarse;
    nodes.x.origin += sx;
    nodes.y.origin += sy;
    const ForwardOperator a = make_averaging_operator_2d(*c.kernel, nodes, lattice, Discretization::coarse_fine);
    return std::array<Eigen::VectorXd, 3>{rho0 * a.apply(vx.cwiseProduct(vx)), rho0 * a.apply(vx.cwiseProduct(vy)),
                                          rho0 * a.apply(vy.cwiseProduct(vy))};
  };
  const auto xp = flux_at(delta, 0), xm = flux_at(-delta, 0), yp = flux_at(0, delta), ym = flux_at(0, -delta);
  const Eigen::VectorXd div_x = (xp[0] - xm[0] + yp[1] - ym[1]) / (2.0 * delta);
  const Eigen::VectorXd div_y = (xp[1] - xm[1] + yp[2] - ym[2]) / (2.0 * delta);
  const double scale = std::max(rate_x.cwiseAbs().maxCoeff(), rate_y.cwiseAbs().maxCoeff());
  EXPECT_GT(scale, 0.1);
  EXPECT_LT((rate_x + div_x).cwiseAbs().maxCoeff(), 1e-5 * scale);
  EXPECT_LT((rate_y + div_y).cwiseAbs().maxCoeff(), 1e-5 * scale);
}
