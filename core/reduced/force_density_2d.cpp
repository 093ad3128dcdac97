// The 2D force-density model, its assembly: the lattice's pair forces and summation-density rate linearised about
// rest, contracted with the window into the maps from the reconstruction to the coarse rates, and the deconvolvers
// bound to the forward operators (core/reduced/force_density_2d.hpp). The steady solve is force_density_2d_solve.cpp,
// the solver section and the checks force_density_2d_schema.cpp.
#include "core/reduced/force_density_2d.hpp"
#include "core/reduced/force_density_2d_assembly.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/repeated_timing.hpp"
#include "core/sph/lattice_stencil.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab {

using namespace force_density_detail;

ForceDensitySolver2D::Interp ForceDensitySolver2D::bilinear_weights(const TensorMesh2D& mesh, const Vec2& q) {
  // Along a periodic axis the two nodes around q wrap; along a bounded one a point beyond the first or last node takes
  // that node's value (only solid particles lie there). A point within 1e-12 spacings of a node is on it, so that a
  // reconstruction on the lattice rows reads exactly its own row.
  const auto axis = [](const UniformMesh1D& m, double c, int& i0, int& i1, double& t) {
    double s = (c - m.origin) / m.spacing;
    const double nearest = std::round(s);
    if (std::abs(s - nearest) < 1e-12) s = nearest;
    const double f = std::floor(s);
    t = s - f;
    const int k = static_cast<int>(f);
    if (m.periodic) {
      i0 = ((k % m.count) + m.count) % m.count;
      i1 = (i0 + 1) % m.count;
    } else {
      i0 = std::clamp(k, 0, m.count - 1);
      i1 = std::clamp(k + 1, 0, m.count - 1);
    }
  };
  int x0, x1, y0, y1;
  double tx, ty;
  axis(mesh.x, q.x(), x0, x1, tx);
  axis(mesh.y, q.y(), y0, y1, ty);
  return {{mesh.index(x0, y0), mesh.index(x1, y0), mesh.index(x0, y1), mesh.index(x1, y1)},
          {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty}};
}

ForceDensitySolver2D::ForceDensitySolver2D(const Scene& scene, const AveragingKernel& kernel, Deconvolver& velocity,
                                           Deconvolver& density, ForceDensity2DOptions options, Integrator* stepper)
    : scene_(scene), velocity_(velocity), density_(density), opt_(std::move(options)), stepper_(stepper) {
  const auto t0 = std::chrono::steady_clock::now();
  check_force_density_2d(scene, kernel, opt_);
  coarse_ = force_density_coarse_mesh(scene, kernel, opt_.spacing_over_eta);
  recon_ =
      force_density_reconstruction_mesh(scene, coarse_, opt_.reconstruction_refinement, opt_.reconstruction_y_nodes);
  const ParticleSystem lattice = scene.make_particles();
  const std::size_t np = lattice.size();
  const int lnx = scene.nx, lny = scene.ny;
  const double dx = scene.dx;
  if (np != static_cast<std::size_t>(lnx) * static_cast<std::size_t>(lny))
    throw ConfigError("/scene", "the 2D force-density model needs one particle per lattice site");
  // Lattice sites: particle a at ((i + ½) ε', (j + ½) ε').
  std::vector<int> site(np, -1);
  for (std::size_t a = 0; a < np; ++a) {
    const long i = std::lround(lattice.x[a] / dx - 0.5), j = std::lround(lattice.y[a] / dx - 0.5);
    if (i < 0 || i >= lnx || j < 0 || j >= lny || std::abs(lattice.x[a] - (i + 0.5) * dx) > 1e-9 * dx ||
        std::abs(lattice.y[a] - (j + 0.5) * dx) > 1e-9 * dx || site[static_cast<std::size_t>(j * lnx + i)] >= 0)
      throw ConfigError("/scene", "the 2D force-density model needs the particles on their lattice sites");
    site[static_cast<std::size_t>(j * lnx + i)] = static_cast<int>(a);
  }
  fixed_ = lattice.fixed;
  // Bilinear weights of every particle on the reconstruction mesh.
  interp_.resize(np);
  for (std::size_t a = 0; a < np; ++a) interp_[a] = bilinear_weights(recon_, Vec2(lattice.x[a], lattice.y[a]));
  double n0 = 0.0;
  const std::vector<LatticeOffset> stencil = lattice_pair_stencil(scene.smoothing_kernel(), dx, n0);
  const double m = scene.particle_mass();
  const double p0 = scene.pressure(n0, m), dn = 1e-6 * n0;
  const double dp_dn = (scene.pressure(n0 + dn, m) - scene.pressure(n0 - dn, m)) / (2.0 * dn);
  const double beta = dp_dn / (n0 * n0) - 2.0 * p0 / (n0 * n0 * n0);
  const bool transport = opt_.pair_forces == SphFormulation::transport_velocity;
  const TransportLinearisation tvf =
      transport ? transport_linearisation(scene, lattice, site, stencil, n0, p0) : TransportLinearisation{};
  const Eigen::Index nc = coarse_.size(), nr = recon_.size();
  const int ncx = coarse_.nx(), nrx = recon_.nx(), nry = recon_.ny();
  Eigen::VectorXd rho_bar = Eigen::VectorXd::Zero(nc), fluid_mass = Eigen::VectorXd::Zero(nc),
                  psi_sum = Eigen::VectorXd::Zero(nc);
  body_x_ = body_y_ = Eigen::VectorXd::Zero(nc);
  // Seven maps M(n, r) = Σ_a ψ(x_n − q_a) row_a(r), row_a a particle's sparse row over the reconstruction nodes:
  // the velocity and density operators (unscaled), the viscous force, the pressure force (x, y), the continuity
  // rate (from V_x, V_y). ψ is separable, so they are contracted lattice row by lattice row: first over the
  // particles of the row with φ(x_i − x_a) into a block (coarse column i × the reconstruction rows the particle
  // rows touch × reconstruction column), then the block with φ(y_j − y_row) into M: O(N · J_x · stencil) +
  // O(rows · J_y · N_C,x · block) instead of O(N · J_x J_y · stencil).
  enum Map { op_v, op_n, visc, press_x, press_y, cont_x, cont_y, map_count };
  std::array<RowMajorMatrix, map_count> maps;  // row-major while accumulating: a block row is contiguous
  for (auto& mat : maps) mat = RowMajorMatrix::Zero(nc, nr);
  std::array<ScratchRow, map_count> rows{ScratchRow(nr), ScratchRow(nr), ScratchRow(nr), ScratchRow(nr),
                                         ScratchRow(nr), ScratchRow(nr), ScratchRow(nr)};
  const auto add_interp = [&](Map k, std::size_t b, double c) {
    for (int u = 0; u < 4; ++u) rows[k].add(interp_[b].node[u], c * interp_[b].weight[u]);
  };
  std::vector<std::vector<std::pair<int, double>>> wx_of_column(static_cast<std::size_t>(lnx));
  for (int i = 0; i < lnx; ++i)
    wx_of_column[static_cast<std::size_t>(i)] = axis_window(kernel, coarse_.x, (i + 0.5) * dx, opt_.window_cutoff);
  // Reconstruction rows one lattice row's particle rows touch (the transport-velocity walls reach two supports).
  const int max_slots = transport ? 32 : 16;
  std::vector<int> slot_of(static_cast<std::size_t>(nry), -1), slot_row;
  std::array<std::vector<double>, map_count> block;
  for (auto& v : block) v.assign(static_cast<std::size_t>(ncx) * max_slots * nrx, 0.0);
  for (int j = 0; j < lny; ++j) {
    const std::vector<std::pair<int, double>> wy = axis_window(kernel, coarse_.y, (j + 0.5) * dx, opt_.window_cutoff);
    for (int i = 0; i < lnx; ++i) {
      const auto a = static_cast<std::size_t>(site[static_cast<std::size_t>(j * lnx + i)]);
      const std::vector<std::pair<int, double>>& wx = wx_of_column[static_cast<std::size_t>(i)];
      const bool fluid = !fixed_[a];
      const double mu_a = scene.phase_viscosity.at(static_cast<std::size_t>(lattice.phase[a]));
      // Particle a's own coefficients, summed over its pairs before they are interpolated once.
      double own_visc = 0.0, own_px = 0.0, own_py = 0.0, own_cx = 0.0, own_cy = 0.0;
      Vec2 affine(0.0, 0.0);  // the transport-velocity walls' force at rest
      for (const LatticeOffset& o : stencil) {
        if (!scene.box.periodic_y && (j + o.dj < 0 || j + o.dj >= lny)) continue;  // beyond a wall's outer face
        const long bi = ((i + o.di) % lnx + lnx) % lnx, bj = ((j + o.dj) % lny + lny) % lny;
        const auto b = static_cast<std::size_t>(site[static_cast<std::size_t>(bj * lnx + bi)]);
        const bool b_fluid = !fixed_[b];
        if (fluid && transport) {  // the transport-velocity pair (header): the wall's ghost velocity and pressure
          const double mu_b = scene.phase_viscosity.at(static_cast<std::size_t>(lattice.phase[b]));
          const double eta_sum = mu_a + mu_b, r2 = o.qx * o.qx + o.qy * o.qy;
          const double vol = tvf.vol2_fluid + (b_fluid ? tvf.vol2_fluid : tvf.vol2_wall);
          // η = ν ρ_rest for both (ν = μ / ρ0): η_ab = 2 η_a η_b / (η_a + η_b).
          const double c =
              eta_sum > 0.0 ? vol * (2.0 * mu_a * mu_b / eta_sum) * tvf.eta_per_mu * o.F * r2 / (r2 + tvf.eps) : 0.0;
          own_visc += c;
          const double bp = 0.5 * dp_dn * vol - tvf.rest_volume_term;  // δn_a's pressure coefficient, β for a fluid b
          own_px -= bp * o.F * o.qx;
          own_py -= bp * o.F * o.qy;
          if (b_fluid) {
            add_interp(visc, b, -c);
            add_interp(press_x, b, -bp * o.F * o.qx);
            add_interp(press_y, b, -bp * o.F * o.qy);
          } else {
            const double gamma = 0.5 * vol;  // ∂p̄/∂p_w (V_a² + V_w²) at rest
            for (const auto& [f, w] : tvf.shepard[b]) {
              add_interp(visc, static_cast<std::size_t>(f), c * w);  // −c v_g, v_g = −Σ_f w V_f
              add_interp(press_x, static_cast<std::size_t>(f), -gamma * dp_dn * w * o.F * o.qx);
              add_interp(press_y, static_cast<std::size_t>(f), -gamma * dp_dn * w * o.F * o.qy);
            }
            // The wall's hydrostatic pressure, and the rest pressure where V_w² differs from 1/n0².
            const double at_rest = gamma * tvf.hydrostatic[b] + p0 * (tvf.vol2_wall - tvf.vol2_fluid);
            affine -= at_rest * o.F * Vec2(o.qx, o.qy);
          }
          own_cx += o.F * o.qx;
          own_cy += o.F * o.qy;
        } else if (fluid) {  // the force on a fluid particle: viscous (V_a − V_b), pressure (δn_a + δn_b)
          const double mu_ab = pair_viscosity(
              mu_a, scene.phase_viscosity.at(static_cast<std::size_t>(lattice.phase[b])), scene.pair_viscosity_mean);
          const double c = mu_ab * o.F / (n0 * n0);
          own_visc += c;
          if (b_fluid) add_interp(visc, b, -c);
          own_px -= beta * o.F * o.qx;
          add_interp(press_x, b, -beta * o.F * o.qx);
          own_py -= beta * o.F * o.qy;
          add_interp(press_y, b, -beta * o.F * o.qy);
          own_cx += o.F * o.qx;  // ṅ_a = Σ_b F q_ab · (V_a − V_b), the solid's velocity zero
          own_cy += o.F * o.qy;
        }
        if (b_fluid) {
          add_interp(cont_x, b, -o.F * o.qx);
          add_interp(cont_y, b, -o.F * o.qy);
        }
      }
      if (fluid) {
        add_interp(visc, a, own_visc);
        add_interp(press_x, a, own_px);
        add_interp(press_y, a, own_py);
        add_interp(cont_x, a, own_cx);
        add_interp(cont_y, a, own_cy);
      }
      if (fluid) add_interp(op_v, a, m);
      add_interp(op_n, a, 1.0);
      for (int k = 0; k < map_count; ++k)
        rows[static_cast<std::size_t>(k)].drain([&](int r, double v) {
          const int ry = r / nrx, rx = r % nrx;
          int& slot = slot_of[static_cast<std::size_t>(ry)];
          if (slot < 0) {
            if (static_cast<int>(slot_row.size()) == max_slots)
              throw std::logic_error("force density map: a lattice row touches too many reconstruction rows");
            slot = static_cast<int>(slot_row.size());
            slot_row.push_back(ry);
          }
          double* out = block[static_cast<std::size_t>(k)].data() + static_cast<std::size_t>(slot) * nrx + rx;
          for (const auto& [ci, fx] : wx) out[static_cast<std::size_t>(ci) * max_slots * nrx] += fx * v;
        });
      const Vec2 g = scene.body_force ? scene.body_force(lattice.x[a], lattice.y[a])
                                      : Vec2(scene.force_x ? scene.force_x(lattice.y[a]) : 0.0, 0.0);
      for (const auto& [cj, fy] : wy)
        for (const auto& [ci, fx] : wx) {
          const Eigen::Index n = coarse_.index(ci, cj);
          const double psi = fx * fy;
          rho_bar[n] += m * psi;
          psi_sum[n] += psi;
          if (fluid) {
            fluid_mass[n] += m * psi;
            body_x_[n] += m * psi * g.x();
            body_y_[n] += m * psi * g.y();
            if (transport) {
              body_x_[n] += psi * affine.x();
              body_y_[n] += psi * affine.y();
            }
          }
        }
    }
    // The row's block into the maps, with φ(y_j − y_row).
    for (int k = 0; k < map_count; ++k) {
      std::vector<double>& blk = block[static_cast<std::size_t>(k)];
      RowMajorMatrix& into = maps[static_cast<std::size_t>(k)];
      for (std::size_t s = 0; s < slot_row.size(); ++s)
        for (int ci = 0; ci < ncx; ++ci) {
          double* src = blk.data() + (static_cast<std::size_t>(ci) * max_slots + s) * nrx;
          for (const auto& [cj, fy] : wy) {
            const Eigen::Index n = coarse_.index(ci, cj);
            const Eigen::Index r0 = static_cast<Eigen::Index>(slot_row[s]) * nrx;
            double* dst = into.data() + n * nr + r0;
            for (int rx = 0; rx < nrx; ++rx) dst[rx] += fy * src[rx];
          }
          std::fill(src, src + nrx, 0.0);
        }
    }
    for (int ry : slot_row) slot_of[static_cast<std::size_t>(ry)] = -1;
    slot_row.clear();
  }
  const Eigen::VectorXd inv_rho = rho_bar.cwiseInverse(), inv_psi = psi_sum.cwiseInverse();
  for (Map k : {op_v, visc, press_x, press_y}) maps[k] = inv_rho.asDiagonal() * maps[k];  // in place
  for (Map k : {op_n, cont_x, cont_y}) maps[k] = inv_psi.asDiagonal() * maps[k];
  body_x_ = body_x_.cwiseProduct(inv_rho);
  body_y_ = body_y_.cwiseProduct(inv_rho);
  if (opt_.convective_stress) assemble_convective(scene, kernel, lattice, rho_bar);
  mass_weight_ = rho_bar * coarse_.cell_area() / (scene.rho0 * scene.box.lx * scene.box.ly);
  fluid_area_per_particle_ = dx * dx / (scene.box.lx * scene.box.ly);
  // Free nodes: a fluid mass fraction of at least hold_fraction; the others are held and reported as the average
  // of the reconstruction.
  for (Eigen::Index n = 0; n < nc; ++n)
    if (fluid_mass[n] >= opt_.hold_fraction * rho_bar[n]) free_.push_back(static_cast<int>(n));
  if (free_.empty()) throw ConfigError("/solver/hold_fraction", "every coarse node is held: no node has fluid enough");
  // The velocity's unknowns: the reconstruction nodes that some fluid particle's interpolation reads; the others
  // lie inside the solid, where the velocity is the known zero (left free they would be fixed by the
  // regularisation alone, and leak into the fluid particles next to the surface).
  for (Eigen::Index r = 0; r < nr; ++r)
    if (maps[op_v].col(r).cwiseAbs().maxCoeff() > 0.0) velocity_columns_.push_back(static_cast<int>(r));
  // The operators: the free rows (and the velocity's unknowns) of A_v and A_n.
  Eigen::MatrixXd a_v_op(static_cast<Eigen::Index>(free_.size()), static_cast<Eigen::Index>(velocity_columns_.size())),
      a_n_op(static_cast<Eigen::Index>(free_.size()), nr);
  for (std::size_t k = 0; k < free_.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    for (std::size_t c = 0; c < velocity_columns_.size(); ++c)
      a_v_op(row, static_cast<Eigen::Index>(c)) = maps[op_v](free_[k], velocity_columns_[c]);
    a_n_op.row(row) = maps[op_n].row(free_[k]);
  }
  op_v_ = ForwardOperator::from_dense(std::move(a_v_op));
  op_n_ = ForwardOperator::from_dense(std::move(a_n_op));
  // The priors of first_difference_zero_ends: the velocity's links viscosity-weighted (the harmonic mean of the two
  // ends' viscosity over the largest, as the 1D model's), its links into the solid to the known zero; the density's
  // links unweighted, every node an unknown.
  std::vector<int> unknown_of(static_cast<std::size_t>(nr), -1);
  for (std::size_t c = 0; c < velocity_columns_.size(); ++c)
    unknown_of[static_cast<std::size_t>(velocity_columns_[c])] = static_cast<int>(c);
  const double mu_max = scene.max_viscosity();
  op_v_.difference_links =
      link_differences(recon_, unknown_of, static_cast<int>(velocity_columns_.size()), [&](int p, int q) {
        const double a = scene.viscosity_at(recon_.node(p)), b = scene.viscosity_at(recon_.node(q));
        return 2.0 * a * b / (a + b) / mu_max;
      });
  for (Eigen::Index r = 0; r < nr; ++r) unknown_of[static_cast<std::size_t>(r)] = static_cast<int>(r);
  op_n_.difference_links = link_differences(recon_, unknown_of, static_cast<int>(nr), [](int, int) { return 1.0; });
  full_v_ = std::move(maps[op_v]);
  full_n_ = std::move(maps[op_n]);
  viscous_ = std::move(maps[visc]);
  pressure_x_ = std::move(maps[press_x]);
  pressure_y_ = std::move(maps[press_y]);
  continuity_x_ = std::move(maps[cont_x]);
  continuity_y_ = std::move(maps[cont_y]);
  assembly_seconds_ = seconds_since(t0);
  try {
    velocity_.setup(op_v_);
    density_.setup(op_n_);
  } catch (const ConfigError& e) {
    throw ConfigError("/closure/deconvolver" + e.path(), e.message());
  }
  vx_ = vy_ = n_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(free_.size()));
  setup_seconds_ = seconds_since(t0);
}

}  // namespace closurelab
