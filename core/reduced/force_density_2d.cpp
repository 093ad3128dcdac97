#include "core/reduced/force_density_2d.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/repeated_timing.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_pair_force.hpp"

namespace closurelab {

ParamSchema force_density_2d_schema() {
  const ForceDensity2DOptions d;  // the defaults
  return {number_param("spacing_over_eta", d.spacing_over_eta, "coarse mesh spacing Delta / eta'", 0.05, 4.0),
          integer_param("reconstruction_refinement", d.reconstruction_refinement,
                        "the reconstruction mesh's spacing is Delta / this (1: the coarse mesh)", 1, 16),
          number_param("window_cutoff", d.window_cutoff,
                       "window values below this fraction of psi(0) are dropped from the assembled maps", 0.0, 1e-3),
          number_param("hold_fraction", d.hold_fraction,
                       "coarse nodes whose window's fluid mass fraction is below this are held: not evolved, not "
                       "deconvolution data",
                       0.0, 0.5),
          string_param("held_node_value", name_of(d.held_node_value),
                       "what a held node reports: imposed (zero) or reconstructed (the average of the reconstruction)",
                       names_of<HeldNodeValue>())};
}

ForceDensity2DOptions force_density_2d_options_from(const json& s) {
  ForceDensity2DOptions o;
  o.spacing_over_eta = s.at("spacing_over_eta").get<double>();
  o.reconstruction_refinement = s.at("reconstruction_refinement").get<int>();
  o.window_cutoff = s.at("window_cutoff").get<double>();
  o.hold_fraction = s.at("hold_fraction").get<double>();
  o.held_node_value = parse_name<HeldNodeValue>(s.at("held_node_value").get<std::string>(), "/solver/held_node_value");
  return o;
}

TensorMesh2D force_density_coarse_mesh(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta) {
  if (!scene.box.periodic_x || !scene.box.periodic_y || scene.has_walls)
    throw ConfigError("/scene", "the 2D force-density model needs a doubly periodic box (solids given by position); "
                                "scene '" + scene.name + "' is not one");
  const double target = spacing_over_eta * kernel.eta();
  const int nx = static_cast<int>(std::lround(scene.box.lx / target));
  const int ny = static_cast<int>(std::lround(scene.box.ly / target));
  if (nx < 4 || ny < 4)
    throw ConfigError("/solver/spacing_over_eta", "fewer than 4 coarse nodes along a side of the box (" +
                                                      std::to_string(nx) + " x " + std::to_string(ny) + ")");
  return {UniformMesh1D::cell_centred(0.0, scene.box.lx, nx, true),
          UniformMesh1D::cell_centred(0.0, scene.box.ly, ny, true)};
}

TensorMesh2D force_density_reconstruction_mesh(const Scene& scene, const TensorMesh2D& coarse, int refinement) {
  const int nx = coarse.nx() * refinement, ny = coarse.ny() * refinement;
  if (nx > scene.nx || ny > scene.ny)
    throw ConfigError("/solver/reconstruction_refinement",
                      "the reconstruction mesh (" + std::to_string(nx) + " x " + std::to_string(ny) +
                          ") is finer than the particle lattice (" + std::to_string(scene.nx) + " x " +
                          std::to_string(scene.ny) + "); lower the refinement");
  return {UniformMesh1D::cell_centred(0.0, scene.box.lx, nx, true),
          UniformMesh1D::cell_centred(0.0, scene.box.ly, ny, true)};
}

void check_force_density_2d(const Scene& scene, const AveragingKernel& kernel, const ForceDensity2DOptions& o) {
  const TensorMesh2D coarse = force_density_coarse_mesh(scene, kernel, o.spacing_over_eta);
  force_density_reconstruction_mesh(scene, coarse, o.reconstruction_refinement);
  if (scene.van_der_waals)
    throw ConfigError("/scene", "the 2D force-density model linearises a weakly compressible equation of state; "
                                "scene '" + scene.name + "' uses van der Waals");
  if (std::abs(scene.box.lx / scene.nx - scene.dx) > 1e-12 * scene.dx ||
      std::abs(scene.box.ly / scene.ny - scene.dx) > 1e-12 * scene.dx)
    throw ConfigError("/scene", "the 2D force-density model needs the square lattice to fill the periodic box");
}

void check_force_density_closure(const json& deconvolver, const std::string& path) {
  const std::string name = deconvolver.value("name", "");
  if (name == "cg" || name == "cgls")
    throw ConfigError(path + "/closure/deconvolver", "the steady solve probes the closure once, which needs it "
                                                     "linear in the data; " + closure_nonlinearity(deconvolver));
  if (deconvolver.value("regularizer", "identity") != "identity")
    throw ConfigError(path + "/closure/deconvolver/regularizer",
                      "the velocity's unknowns are the reconstruction nodes outside the solid, not a tensor mesh: "
                      "difference regularizers do not apply (use identity)");
}

namespace {

// A row over the reconstruction nodes, accumulated densely and read back sparsely.
class ScratchRow {
 public:
  explicit ScratchRow(Eigen::Index n) : value_(Eigen::VectorXd::Zero(n)), seen_(static_cast<std::size_t>(n), 0) {}
  void add(int node, double v) {
    if (!seen_[static_cast<std::size_t>(node)]) {
      seen_[static_cast<std::size_t>(node)] = 1;
      touched_.push_back(node);
    }
    value_[node] += v;
  }
  // Calls f(node, value) for each entry, then clears.
  template <class F>
  void drain(F f) {
    for (int n : touched_) {
      if (value_[n] != 0.0) f(n, value_[n]);
      value_[n] = 0.0;
      seen_[static_cast<std::size_t>(n)] = 0;
    }
    touched_.clear();
  }

 private:
  Eigen::VectorXd value_;
  std::vector<std::uint8_t> seen_;
  std::vector<int> touched_;
};

// The Gaussian window's 1D factor at the nodes of a periodic axis around q, periodic images summed; factors below
// cutoff · φ(0) are dropped.
std::vector<std::pair<int, double>> axis_window(const AveragingKernel& kernel, const UniformMesh1D& axis, double q,
                                                double cutoff) {
  std::vector<std::pair<int, double>> out;
  for_nodes_within(axis, q, kernel.support_radius(), [&](int n, double d) { out.emplace_back(n, kernel.factor(d)); });
  // for_nodes_within visits each image separately: merge the images of one node, then drop the tail.
  std::sort(out.begin(), out.end());
  std::size_t k = 0;
  for (std::size_t u = 0; u < out.size(); ++u) {
    if (k > 0 && out[k - 1].first == out[u].first)
      out[k - 1].second += out[u].second;
    else
      out[k++] = out[u];
  }
  out.resize(k);
  const double drop = cutoff * kernel.factor(0.0);
  out.erase(std::remove_if(out.begin(), out.end(), [&](const auto& e) { return e.second < drop; }), out.end());
  return out;
}

// The SPH pair stencil of the square lattice of spacing dx: the offsets within the smoothing function's support,
// with F = w'(r)/r and q_ab = q_a − q_b = −(di, dj) dx; n0 = Σ w, the lattice's number density.
struct Offset {
  int di, dj;
  double F, qx, qy;
};
std::vector<Offset> pair_stencil(const SmoothingKernel& w, double dx, double& n0) {
  std::vector<Offset> stencil;
  n0 = w.w(0.0);
  const int reach = static_cast<int>(std::ceil(w.support() / dx));
  for (int dj = -reach; dj <= reach; ++dj)
    for (int di = -reach; di <= reach; ++di) {
      const double r = std::hypot(di, dj) * dx;
      if ((di == 0 && dj == 0) || r >= w.support()) continue;
      stencil.push_back({di, dj, w.dw(r) / r, -di * dx, -dj * dx});
      n0 += w.w(r);
    }
  return stencil;
}

}  // namespace

ForceDensitySolver2D::Interp ForceDensitySolver2D::bilinear_weights(const TensorMesh2D& mesh, const Vec2& q) {
  const auto axis = [](const UniformMesh1D& m, double c, int& i0, int& i1, double& t) {
    const double s = (c - m.origin) / m.spacing;
    const double f = std::floor(s);
    t = s - f;
    i0 = ((static_cast<int>(f) % m.count) + m.count) % m.count;
    i1 = (i0 + 1) % m.count;
  };
  int x0, x1, y0, y1;
  double tx, ty;
  axis(mesh.x, q.x(), x0, x1, tx);
  axis(mesh.y, q.y(), y0, y1, ty);
  return {{mesh.index(x0, y0), mesh.index(x1, y0), mesh.index(x0, y1), mesh.index(x1, y1)},
          {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty}};
}

ForceDensitySolver2D::ForceDensitySolver2D(const Scene& scene, const AveragingKernel& kernel, Deconvolver& velocity,
                                           Deconvolver& density, ForceDensity2DOptions options)
    : scene_(scene), velocity_(velocity), density_(density), opt_(std::move(options)) {
  const auto t0 = std::chrono::steady_clock::now();
  check_force_density_2d(scene, kernel, opt_);
  coarse_ = force_density_coarse_mesh(scene, kernel, opt_.spacing_over_eta);
  recon_ = force_density_reconstruction_mesh(scene, coarse_, opt_.reconstruction_refinement);
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
  // Bilinear weights of every particle on the periodic reconstruction mesh.
  interp_.resize(np);
  for (std::size_t a = 0; a < np; ++a) interp_[a] = bilinear_weights(recon_, Vec2(lattice.x[a], lattice.y[a]));
  double n0 = 0.0;
  const std::vector<Offset> stencil = pair_stencil(scene.smoothing_kernel(), dx, n0);
  const double m = scene.particle_mass();
  const double p0 = scene.pressure(n0, m), dn = 1e-6 * n0;
  const double dp_dn = (scene.pressure(n0 + dn, m) - scene.pressure(n0 - dn, m)) / (2.0 * dn);
  const double beta = dp_dn / (n0 * n0) - 2.0 * p0 / (n0 * n0 * n0);
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
  for (int i = 0; i < lnx; ++i) wx_of_column[static_cast<std::size_t>(i)] = axis_window(kernel, coarse_.x, (i + 0.5) * dx, opt_.window_cutoff);
  constexpr int max_slots = 16;  // reconstruction rows one lattice row's particle rows touch
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
      for (const Offset& o : stencil) {
        const long bi = ((i + o.di) % lnx + lnx) % lnx, bj = ((j + o.dj) % lny + lny) % lny;
        const auto b = static_cast<std::size_t>(site[static_cast<std::size_t>(bj * lnx + bi)]);
        const bool b_fluid = !fixed_[b];
        if (fluid) {  // the force on a fluid particle: viscous (V_a − V_b), pressure (δn_a + δn_b)
          const double mu_ab = pair_viscosity(
              mu_a, scene.phase_viscosity.at(static_cast<std::size_t>(lattice.phase[b])), scene.pair_viscosity_mean);
          const double c = mu_ab * o.F / (n0 * n0);
          add_interp(visc, a, c);
          if (b_fluid) add_interp(visc, b, -c);
          add_interp(press_x, a, -beta * o.F * o.qx);
          add_interp(press_x, b, -beta * o.F * o.qx);
          add_interp(press_y, a, -beta * o.F * o.qy);
          add_interp(press_y, b, -beta * o.F * o.qy);
          add_interp(cont_x, a, o.F * o.qx);  // ṅ_a = Σ_b F q_ab · (V_a − V_b), the solid's velocity zero
          add_interp(cont_y, a, o.F * o.qy);
        }
        if (b_fluid) {
          add_interp(cont_x, b, -o.F * o.qx);
          add_interp(cont_y, b, -o.F * o.qy);
        }
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
  Eigen::MatrixXd a_v = maps[op_v], a_n = maps[op_n];
  viscous_ = std::move(maps[visc]);
  pressure_x_ = std::move(maps[press_x]);
  pressure_y_ = std::move(maps[press_y]);
  continuity_x_ = std::move(maps[cont_x]);
  continuity_y_ = std::move(maps[cont_y]);
  const Eigen::VectorXd inv_rho = rho_bar.cwiseInverse(), inv_psi = psi_sum.cwiseInverse();
  for (auto* mat : {&viscous_, &pressure_x_, &pressure_y_}) *mat = inv_rho.asDiagonal() * *mat;  // in place
  for (auto* mat : {&continuity_x_, &continuity_y_}) *mat = inv_psi.asDiagonal() * *mat;
  body_x_ = body_x_.cwiseProduct(inv_rho);
  body_y_ = body_y_.cwiseProduct(inv_rho);
  a_v = inv_rho.asDiagonal() * a_v;
  a_n = inv_psi.asDiagonal() * a_n;
  mass_weight_ = rho_bar * coarse_.cell_area() / (scene.rho0 * scene.box.lx * scene.box.ly);
  fluid_area_per_particle_ = dx * dx / (scene.box.lx * scene.box.ly);
  // Free nodes: a fluid mass fraction of at least hold_fraction; the others are held and reported as the average
  // of the reconstruction.
  for (Eigen::Index n = 0; n < nc; ++n)
    if (fluid_mass[n] >= opt_.hold_fraction * rho_bar[n]) free_.push_back(static_cast<int>(n));
  if (free_.empty()) throw ConfigError("/solver/hold_fraction", "every coarse node is held: no node has fluid enough");
  full_v_ = a_v;
  full_n_ = a_n;
  const auto free_rows = [&](const Eigen::MatrixXd& full) {
    Eigen::MatrixXd out(static_cast<Eigen::Index>(free_.size()), full.cols());
    for (std::size_t k = 0; k < free_.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = full.row(free_[k]);
    return out;
  };
  // The velocity's unknowns: the reconstruction nodes that some fluid particle's interpolation reads; the others
  // lie inside the solid, where the velocity is the known zero (left free they would be fixed by the
  // regularisation alone, and leak into the fluid particles next to the surface).
  for (Eigen::Index r = 0; r < nr; ++r)
    if (a_v.col(r).cwiseAbs().maxCoeff() > 0.0) velocity_columns_.push_back(static_cast<int>(r));
  const Eigen::MatrixXd a_v_free = free_rows(a_v);
  Eigen::MatrixXd a_v_op(a_v_free.rows(), static_cast<Eigen::Index>(velocity_columns_.size()));
  for (std::size_t k = 0; k < velocity_columns_.size(); ++k)
    a_v_op.col(static_cast<Eigen::Index>(k)) = a_v_free.col(velocity_columns_[k]);
  op_v_ = ForwardOperator::from_dense(std::move(a_v_op));
  op_n_ = ForwardOperator::from_dense(free_rows(a_n));
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

void ForceDensitySolver2D::set_state(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy, const Eigen::VectorXd& n) {
  const Eigen::Index nc = coarse_.size();
  if (vx.size() != nc || vy.size() != nc || n.size() != nc) throw ConfigError("", "state has the wrong size");
  for (std::size_t k = 0; k < free_.size(); ++k) {
    vx_[static_cast<Eigen::Index>(k)] = vx[free_[k]];
    vy_[static_cast<Eigen::Index>(k)] = vy[free_[k]];
    n_[static_cast<Eigen::Index>(k)] = n[free_[k]];
  }
}

Eigen::VectorXd ForceDensitySolver2D::interpolate_to_particles(const Eigen::VectorXd& x) const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(interp_.size()));
  for (std::size_t a = 0; a < interp_.size(); ++a) {
    double v = 0.0;
    for (int k = 0; k < 4; ++k) v += interp_[a].weight[k] * x[interp_[a].node[k]];
    out[static_cast<Eigen::Index>(a)] = v;
  }
  return out;
}

bool ForceDensitySolver2D::deconvolve(Deconvolver& d, const Eigen::VectorXd& data, Eigen::VectorXd& x,
                                      std::string& issue) {
  const auto t0 = std::chrono::steady_clock::now();
  const DeconvolutionResult r = d.solve(data, opt_.noise_level);
  matvecs_ += r.cost.matvecs;
  deconvolution_issues_.count(r);
  deconv_seconds_ += seconds_since(t0);
  if (&d == &velocity_) {  // on every reconstruction node: zero inside the solid
    x = Eigen::VectorXd::Zero(recon_.size());
    for (std::size_t k = 0; k < velocity_columns_.size(); ++k) x[velocity_columns_[k]] = r.x[static_cast<Eigen::Index>(k)];
  } else {
    x = r.x;
  }
  if (!x.allFinite()) {
    issue = "deconvolution returned non-finite values (" + r.stats.message + ")";
    return false;
  }
  return true;
}

Eigen::VectorXd ForceDensitySolver2D::on_free(const Eigen::VectorXd& full) const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(free_.size()));
  for (std::size_t k = 0; k < free_.size(); ++k) out[static_cast<Eigen::Index>(k)] = full[free_[k]];
  return out;
}

bool ForceDensitySolver2D::rate(Eigen::VectorXd& ax, Eigen::VectorXd& ay, Eigen::VectorXd& an, std::string& issue) {
  Eigen::VectorXd rx, ry, rn;
  if (!deconvolve(velocity_, vx_, rx, issue) || !deconvolve(velocity_, vy_, ry, issue) ||
      !deconvolve(density_, n_, rn, issue))
    return false;
  Eigen::VectorXd fx, fy, fn;
  rates_from_reconstruction(rx, ry, rn, fx, fy, fn);
  ax = on_free(fx);
  ay = on_free(fy);
  an = on_free(fn);
  return true;
}

void ForceDensitySolver2D::rates_from_reconstruction(const Eigen::VectorXd& rx, const Eigen::VectorXd& ry,
                                                     const Eigen::VectorXd& rn, Eigen::VectorXd& ax,
                                                     Eigen::VectorXd& ay, Eigen::VectorXd& an) const {
  ax = viscous_ * rx + pressure_x_ * rn + body_x_;
  ay = viscous_ * ry + pressure_y_ * rn + body_y_;
  an = continuity_x_ * rx + continuity_y_ * ry;
}

bool ForceDensitySolver2D::steady_solve(std::string& issue) {
  // The rate is affine in the state z = (v̄_x, v̄_y, n̄) on the free nodes: rate = M z + c. Probed on unit data
  // (the closure is linear: check_force_density_closure), then M z = −c solved with the total density deviation
  // Σ n̄ ρ̄-weights = 0 bordering it: the rate does not see a uniform n̄ (a uniform pressure exerts no force on
  // the lattice), so M has that null direction.
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index f = static_cast<Eigen::Index>(free_.size()), nr = recon_.size();
  Eigen::MatrixXd xv(nr, f), xn(nr, f);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(f), x;
  for (Eigen::Index k = 0; k < f; ++k) {
    e[k] = 1.0;
    if (!deconvolve(velocity_, e, x, issue)) return false;
    xv.col(k) = x;
    if (!deconvolve(density_, e, x, issue)) return false;
    xn.col(k) = x;
    e[k] = 0.0;
  }
  Eigen::VectorXd zero = Eigen::VectorXd::Zero(f), x0v, x0n;  // the closure's response to zero data (affine part)
  if (!deconvolve(velocity_, zero, x0v, issue) || !deconvolve(density_, zero, x0n, issue)) return false;
  // The blocks of M on every node (a product of the full map, no copy of it), then the free rows.
  const auto free_rows_of = [&](const Eigen::MatrixXd& full) {
    Eigen::MatrixXd out(f, full.cols());
    for (Eigen::Index k = 0; k < f; ++k) out.row(k) = full.row(free_[static_cast<std::size_t>(k)]);
    return out;
  };
  const Eigen::MatrixXd mvv = free_rows_of(viscous_ * xv), mxn = free_rows_of(pressure_x_ * xn),
                        myn = free_rows_of(pressure_y_ * xn), mnx = free_rows_of(continuity_x_ * xv),
                        mny = free_rows_of(continuity_y_ * xv);
  Eigen::MatrixXd big = Eigen::MatrixXd::Zero(3 * f + 1, 3 * f + 1);
  big.block(0, 0, f, f) = mvv;
  big.block(0, 2 * f, f, f) = mxn;
  big.block(f, f, f, f) = mvv;
  big.block(f, 2 * f, f, f) = myn;
  big.block(2 * f, 0, f, f) = mnx;
  big.block(2 * f, f, f, f) = mny;
  Eigen::VectorXd weight = on_free(mass_weight_);
  big.block(2 * f, 3 * f, f, 1).setConstant(1.0);  // the multiplier of the free direction
  big.block(3 * f, 2 * f, 1, f) = weight.transpose();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * f + 1);
  rhs.segment(0, f) = -on_free(viscous_ * x0v + pressure_x_ * x0n + body_x_);
  rhs.segment(f, f) = -on_free(viscous_ * x0v + pressure_y_ * x0n + body_y_);
  rhs.segment(2 * f, f) = -on_free(continuity_x_ * x0v + continuity_y_ * x0v);
  probe_seconds_ = seconds_since(t0);
  // Equilibrated (rows, then columns, to unit largest entry): the momentum and density rows differ in units, and
  // free nodes with a small fluid fraction have small rows; the condition estimate is then of the problem itself.
  const Eigen::VectorXd row_scale = big.rowwise().lpNorm<Eigen::Infinity>().cwiseMax(1e-300).cwiseInverse();
  big = row_scale.asDiagonal() * big;
  const Eigen::VectorXd col_scale = big.colwise().lpNorm<Eigen::Infinity>().transpose().cwiseMax(1e-300).cwiseInverse();
  big = big * col_scale.asDiagonal();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(big);
  const Eigen::VectorXd z = col_scale.cwiseProduct(lu.solve(row_scale.cwiseProduct(rhs)));
  if (!z.allFinite() || lu.rcond() < 1e-15) {
    std::ostringstream os;
    os << "the steady system is singular to working precision (reciprocal condition " << lu.rcond() << ")";
    issue = os.str();
    return false;
  }
  vx_ = z.segment(0, f);
  vy_ = z.segment(f, f);
  n_ = z.segment(2 * f, f);
  return true;
}

double ForceDensitySolver2D::superficial_velocity(std::string& issue) {
  Eigen::VectorXd rx;
  if (!deconvolve(velocity_, vx_, rx, issue)) return std::nan("");
  const Eigen::VectorXd v = interpolate_to_particles(rx);
  double sum = 0.0;
  for (Eigen::Index a = 0; a < v.size(); ++a)
    if (!fixed_[static_cast<std::size_t>(a)]) sum += v[a];
  return sum * fluid_area_per_particle_;
}

Eigen::VectorXd ForceDensitySolver2D::reported(const Eigen::VectorXd& state, Deconvolver& d,
                                               const Eigen::MatrixXd& full, std::string& issue) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(coarse_.size()), x;
  if (opt_.held_node_value == HeldNodeValue::reconstructed && free_.size() < static_cast<std::size_t>(coarse_.size())) {
    if (!deconvolve(d, state, x, issue)) return Eigen::VectorXd::Constant(coarse_.size(), std::nan(""));
    out = full * x;  // held nodes: the average of the reconstruction
  }
  for (std::size_t k = 0; k < free_.size(); ++k) out[free_[k]] = state[static_cast<Eigen::Index>(k)];
  return out;
}

ForceDensity2DResult ForceDensitySolver2D::run() {
  ForceDensity2DResult res;
  std::string issue;
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = steady_solve(issue);
  res.status = ok ? Status::converged : Status::numerical_issue;
  res.message = issue;
  res.wall_seconds = seconds_since(t0);
  res.mesh = coarse_;
  res.vx = reported(vx_, velocity_, full_v_, issue);
  res.vy = reported(vy_, velocity_, full_v_, issue);
  res.density = reported(n_, density_, full_n_, issue);
  res.superficial_velocity = superficial_velocity(issue);
  if (res.status == Status::converged && (!res.vx.allFinite() || !res.vy.allFinite())) {
    res.status = Status::numerical_issue;
    res.message = issue;
  }
  res.free_nodes = static_cast<long>(free_.size());
  res.deconvolution_matvecs = matvecs_;
  res.deconvolution_issues = deconvolution_issues_;
  res.deconvolution_seconds = deconv_seconds_;
  res.setup_seconds = setup_seconds_;
  res.assembly_seconds = assembly_seconds_;
  res.probe_seconds = probe_seconds_;
  return res;
}

}  // namespace closurelab
