#include "core/sph/linearised_steady.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/base/errors.hpp"
#include "core/sph/lattice_stencil.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Particle a's lattice site (i, j), or (−1, −1) when it is not on one.
std::pair<long, long> site_of(const Scene& scene, const ParticleSystem& ps, std::size_t a) {
  const double dx = scene.dx;
  const long i = std::lround(ps.x[a] / dx - 0.5), j = std::lround(ps.y[a] / dx - 0.5);
  if (i < 0 || i >= scene.nx || j < 0 || j >= scene.ny || std::abs(ps.x[a] - (i + 0.5) * dx) > 1e-9 * dx ||
      std::abs(ps.y[a] - (j + 0.5) * dx) > 1e-9 * dx)
    return {-1, -1};
  return {i, j};
}

}  // namespace

void check_linearised_steady(const Scene& scene, const std::string& path) {
  if (scene.wall_model != WallModel::zero_velocity)
    throw ConfigError(path + "/wall_model",
                      "the linearised steady solve holds the solids at their prescribed "
                      "velocity (zero_velocity); got " +
                          name_of(scene.wall_model));
  if (scene.van_der_waals)
    throw ConfigError(path, "the linearised steady solve takes the weakly compressible equation of state; scene '" +
                                scene.name + "' has the van der Waals one");
  if (scene.position_perturbation != 0.0)
    throw ConfigError(path + "/perturbation", "the linearised steady solve needs the particles on their lattice sites");
  if (!scene.box.periodic_x)
    throw ConfigError(path, "the linearised steady solve takes a box periodic in x (walls, if any, in y)");
}

LinearisedSteadyResult solve_linearised_steady(const Scene& scene, ParticleSystem& ps) {
  check_linearised_steady(scene, "/scene");
  LinearisedSteadyResult st;
  auto t0 = Clock::now();
  const int lnx = scene.nx, lny = scene.ny;
  const std::size_t np = ps.size();
  if (np != static_cast<std::size_t>(lnx) * static_cast<std::size_t>(lny))
    throw ConfigError("/scene", "the linearised steady solve needs one particle per lattice site");
  std::vector<int> at_site(np, -1);
  for (std::size_t a = 0; a < np; ++a) {
    const auto [i, j] = site_of(scene, ps, a);
    if (i < 0 || at_site[static_cast<std::size_t>(j * lnx + i)] >= 0)
      throw ConfigError("/scene", "the linearised steady solve needs the particles on their lattice sites");
    at_site[static_cast<std::size_t>(j * lnx + i)] = static_cast<int>(a);
  }
  double n0 = 0.0;
  const std::vector<LatticeOffset> stencil = lattice_pair_stencil(scene.smoothing_kernel(), scene.dx, n0);
  const double m = scene.particle_mass();
  const double p0 = scene.pressure(n0, m), dn = 1e-6 * n0;
  const double dp_dn = (scene.pressure(n0 + dn, m) - scene.pressure(n0 - dn, m)) / (2.0 * dn);
  const double beta = dp_dn / (n0 * n0) - 2.0 * p0 / (n0 * n0 * n0);
  // The neighbour of particle a at offset o (−1 beyond a wall's outer face).
  const auto neighbour = [&](std::size_t a, const LatticeOffset& o) -> int {
    const auto [i, j] = site_of(scene, ps, a);
    if (!scene.box.periodic_y && (j + o.dj < 0 || j + o.dj >= lny)) return -1;
    const long bi = ((i + o.di) % lnx + lnx) % lnx, bj = ((j + o.dj) % lny + lny) % lny;
    return at_site[static_cast<std::size_t>(bj * lnx + bi)];
  };
  // Unknowns: V_x, V_y and δn of each moving particle; the fixed particles keep n0 (δn = 0, see the header).
  std::vector<int> vel(np, -1), den(np, -1);
  int nu = 0, nd = 0;
  for (std::size_t a = 0; a < np; ++a)
    if (!ps.fixed[a]) {
      vel[a] = nu;
      nu += 2;
    }
  for (std::size_t a = 0; a < np; ++a)
    if (!ps.fixed[a]) den[a] = nu + nd++;
  st.velocity_unknowns = nu;
  st.density_unknowns = nd;
  const int n = nu + nd;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(n) * 2 * stencil.size());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (std::size_t a = 0; a < np; ++a) {
    const int va = vel[a], da = den[a];
    const double mu_a = scene.phase_viscosity.at(static_cast<std::size_t>(ps.phase[a]));
    for (const LatticeOffset& o : stencil) {
      const int bi = neighbour(a, o);
      if (bi < 0) continue;
      const auto b = static_cast<std::size_t>(bi);
      const int vb = vel[b], db = den[b];
      if (va >= 0) {
        // −f_a: viscous −c (V_a − V_b), c = μ_ab F / n0² < 0; pressure +β (δn_a + δn_b) F q.
        const double mu_ab = pair_viscosity(mu_a, scene.phase_viscosity.at(static_cast<std::size_t>(ps.phase[b])),
                                            scene.pair_viscosity_mean);
        const double coef = -mu_ab * o.F / (n0 * n0);
        for (int c = 0; c < 2; ++c) {
          t.emplace_back(va + c, va + c, coef);
          if (vb >= 0)
            t.emplace_back(va + c, vb + c, -coef);
          else
            rhs[va + c] += coef * (c == 0 ? ps.vx[b] : ps.vy[b]);
          const double fq = beta * o.F * (c == 0 ? o.qx : o.qy);
          if (da >= 0) t.emplace_back(va + c, da, fq);
          if (db >= 0) t.emplace_back(va + c, db, fq);
        }
      }
      if (da >= 0) {  // β ṅ_a = β Σ_b F q · (V_a − V_b), the fixed particles' velocities known
        const double fqx = beta * o.F * o.qx, fqy = beta * o.F * o.qy;
        if (va >= 0) {
          t.emplace_back(da, va, fqx);
          t.emplace_back(da, va + 1, fqy);
        } else {
          rhs[da] -= fqx * ps.vx[a] + fqy * ps.vy[a];
        }
        if (vb >= 0) {
          t.emplace_back(da, vb, -fqx);
          t.emplace_back(da, vb + 1, -fqy);
        } else {
          rhs[da] += fqx * ps.vx[b] + fqy * ps.vy[b];
        }
      }
    }
    if (va >= 0) {
      const Vec2 g = scene.body_force ? scene.body_force(ps.x[a], ps.y[a])
                                      : Vec2(scene.force_x ? scene.force_x(ps.y[a]) : 0.0, 0.0);
      rhs[va] += m * g.x();
      rhs[va + 1] += m * g.y();
    }
  }
  Eigen::SparseMatrix<double> system(n, n);
  system.setFromTriplets(t.begin(), t.end());
  st.nonzeros = system.nonZeros();
  // δ: 1e-10 of the Schur complement's scale (β F q)² / (μ F / n0²) at the stencil's largest entries.
  double a_scale = 0.0, b_scale = 0.0;
  for (const LatticeOffset& o : stencil) {
    a_scale = std::max(a_scale, std::abs(scene.max_viscosity() * o.F / (n0 * n0)));
    b_scale = std::max(b_scale, std::abs(beta * o.F) * std::hypot(o.qx, o.qy));
  }
  const double delta = 1e-10 * b_scale * b_scale / a_scale;
  Eigen::SparseMatrix<double> density_block(n, n);  // the δn block's diagonal
  {
    std::vector<Eigen::Triplet<double>> d;
    for (int k = nu; k < n; ++k) d.emplace_back(k, k, delta);
    density_block.setFromTriplets(d.begin(), d.end());
  }
  const Eigen::SparseMatrix<double> regularised = system - density_block;
  st.assemble_seconds = since(t0);

  t0 = Clock::now();
  // CHOLMOD's simplicial LDLᵀ (no pivoting: the regularised system is quasi-definite, so any symmetric ordering
  // factors it) under METIS's nested dissection.
  Eigen::CholmodSimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt;
  ldlt.cholmod().nmethods = 1;
  ldlt.cholmod().method[0].ordering = CHOLMOD_METIS;
  ldlt.compute(regularised);
  st.factor_nonzeros = static_cast<long>(ldlt.cholmod().lnz);
  st.factor_seconds = since(t0);
  if (ldlt.info() != Eigen::Success) {
    st.message = "CHOLMOD could not factor the regularised steady system";
    return st;
  }
  t0 = Clock::now();
  const double scale = rhs.cwiseAbs().maxCoeff();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), r = rhs;
  st.relative_residual = scale > 0.0 ? 1.0 : 0.0;
  // Refined against the unregularised system until the residual is below 1e-12 or stops falling (round-off).
  while (scale > 0.0 && st.refinements < 30 && st.relative_residual > 1e-12) {
    x += ldlt.solve(r);
    r = rhs - system * x;
    const double previous = st.relative_residual;
    st.relative_residual = r.cwiseAbs().maxCoeff() / scale;
    ++st.refinements;
    if (st.relative_residual > 0.5 * previous) break;
  }
  st.solve_seconds = since(t0);
  st.converged = x.allFinite() && st.relative_residual <= 1e-10;
  if (!st.converged) {
    st.message = "the refined steady solve stopped at a relative residual of " + std::to_string(st.relative_residual);
    return st;
  }
  st.density_deviation = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(np));
  for (std::size_t a = 0; a < np; ++a) {
    const auto k = static_cast<Eigen::Index>(a);
    if (den[a] >= 0) st.density_deviation[k] = x[den[a]];
    if (vel[a] >= 0) {
      ps.vx[a] = x[vel[a]];
      ps.vy[a] = x[vel[a] + 1];
    }
  }
  return st;
}

}  // namespace closurelab
