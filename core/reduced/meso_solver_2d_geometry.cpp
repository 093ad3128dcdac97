// The 2D reduced model's solver section (schema and reader) and its doubly periodic geometry: the coarse mesh, the
// staggered faces, the face difference and interpolation with the divergence's symbol, and the lattice's
// pressure-stress factor (core/reduced/meso_solver_2d.hpp).
#include <cmath>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/option_table.hpp"
#include "core/reduced/meso_solver_2d.hpp"

namespace closurelab {
namespace {

const OptionTable<MesoSolver2DOptions>& meso_solver_2d_options() {
  using O = MesoSolver2DOptions;
  static const OptionTable<O> table =
      OptionTable<O>("/solver")
          .number("kappa", &O::kappa, "time-step coefficient of (5.21)-(5.22) (2D: half the 1D default)", 0.0, 1.0, true)
          .number("spacing_over_eta", &O::spacing_over_eta, "coarse mesh spacing / eta' (paper: 1)", 0.05, 4.0)
          .integer("divergence_order", &O::divergence_order,
                   "order of the staggered face-flux difference: 2 or 4 (both conservative, same face values)", 2, 4)
          .choice("equations", &O::equations,
                  "momentum: the linear model (density and pressure the lattice's, no convective stress); "
                  "mass_momentum: the averaged balances (2.10)-(2.11) in (rho, rho v), with the convective flux of "
                  "the closure's velocities (2.12) and the pressure of the coarse density; incompressible: the convective flux and "
                  "the pressure as the multiplier of a discrete projection (core/reduced/meso_solver_2d.hpp)")
          .boolean("transport", &O::transport,
                   "mass_momentum: the mass flux (2.10) and the convective flux (2.11)-(2.12) (false: rho fixed); "
                   "incompressible: the convective flux")
          .boolean("coarse_pressure", &O::coarse_pressure,
                   "mass_momentum: the pressure of the coarse density, -c_lat P(rho) I (false: the lattice's P*)")
          .unbound(entry_param(
              "time_integration", "explicit",
              "the registered integrator that steps the coarse state (closurelab list integrator), a name or "
              "{\"name\": ..., its parameters}; mass_momentum needs one whose stability region holds the imaginary "
              "axis (arkode_erk), not explicit; arkode_imex takes the viscous part div T_int implicitly, the rest "
              "explicitly"))
          .time_loop()
          .check([](const O& o) {
            if (o.divergence_order != 2 && o.divergence_order != 4)
              throw ConfigError("/solver/divergence_order",
                                "must be 2 or 4; got " + std::to_string(o.divergence_order));
          });
  return table;
}

}  // namespace

ParamSchema meso_solver_2d_schema() { return meso_solver_2d_options().schema(); }

MesoSolver2DOptions meso_2d_options_from(const json& s) { return meso_solver_2d_options().read(s); }

TensorMesh2D coarse_mesh_2d(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta) {
  if (scene.has_walls || !scene.box.periodic_x || !scene.box.periodic_y)
    throw ConfigError("/scene", "the 2D reduced model needs a doubly periodic box without walls; scene '" + scene.name +
                                    "' is not one");
  const double target = spacing_over_eta * kernel.eta();
  check_mesh_2d_memory(std::round(scene.box.lx / target), std::round(scene.box.ly / target), "/solver/spacing_over_eta");
  const int nx = static_cast<int>(std::lround(scene.box.lx / target));
  const int ny = static_cast<int>(std::lround(scene.box.ly / target));
  if (nx < 4 || ny < 4)
    throw ConfigError("/solver/spacing_over_eta", "fewer than 4 coarse nodes along a side of the box (" +
                                                      std::to_string(nx) + " x " + std::to_string(ny) + ")");
  return {UniformMesh1D::cell_centred(0.0, scene.box.lx, nx, true),
          UniformMesh1D::cell_centred(0.0, scene.box.ly, ny, true)};
}

TensorMesh2D x_faces_of(const TensorMesh2D& c) {
  TensorMesh2D f = c;
  f.x.origin -= 0.5 * c.x.spacing;  // i Δ: the left face of cell i
  return f;
}

TensorMesh2D y_faces_of(const TensorMesh2D& c) {
  TensorMesh2D f = c;
  f.y.origin -= 0.5 * c.y.spacing;
  return f;
}

Eigen::VectorXd face_difference(const TensorMesh2D& cells, const Eigen::VectorXd& on_faces, int axis, int order) {
  const int nx = cells.nx(), ny = cells.ny();
  const double h = axis == 0 ? cells.x.spacing : cells.y.spacing;
  const auto at = [&](int i, int j) {  // periodic
    return on_faces[cells.index((i % nx + nx) % nx, (j % ny + ny) % ny)];
  };
  const int di = axis == 0 ? 1 : 0, dj = axis == 0 ? 0 : 1;
  Eigen::VectorXd out(cells.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double inner = at(i + di, j + dj) - at(i, j);  // faces i + 1 and i of cell i
      out[cells.index(i, j)] =
          order == 4 ? (27.0 * inner - (at(i + 2 * di, j + 2 * dj) - at(i - di, j - dj))) / (24.0 * h) : inner / h;
    }
  return out;
}

Eigen::VectorXd to_faces(const TensorMesh2D& cells, const Eigen::VectorXd& c, int axis, int order) {
  const int nx = cells.nx(), ny = cells.ny();
  const auto at = [&](int i, int j) { return c[cells.index((i % nx + nx) % nx, (j % ny + ny) % ny)]; };
  const int di = axis == 0 ? 1 : 0, dj = axis == 0 ? 0 : 1;
  Eigen::VectorXd out(cells.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double inner = at(i - di, j - dj) + at(i, j);  // the two cells either side of face i
      out[cells.index(i, j)] =
          order == 4 ? (9.0 * inner - (at(i - 2 * di, j - 2 * dj) + at(i + di, j + dj))) / 16.0 : 0.5 * inner;
    }
  return out;
}

std::vector<double> divergence_symbol(int n, double h, int order) {
  if (order == 2) return PeriodicProjection2D::central_symbol(n, h);
  std::vector<double> s(static_cast<std::size_t>(n));
  for (int m = 0; m < n; ++m) {
    const double th = 2.0 * M_PI * m / n;
    const double interpolation = (9.0 * std::cos(0.5 * th) - std::cos(1.5 * th)) / 8.0;
    s[m] = interpolation * (27.0 * std::sin(0.5 * th) - std::sin(1.5 * th)) / (12.0 * h);
  }
  s[0] = 0.0;
  if (n % 2 == 0) s[n / 2] = 0.0;  // the interpolation's symbol vanishes there
  return s;
}

double lattice_pressure_factor(const Scene& scene) {
  const SmoothingKernel w = scene.smoothing_kernel();
  const int reach = static_cast<int>(std::ceil(w.support() / scene.dx)) + 1;
  double n = 0.0, virial = 0.0;
  for (int j = -reach; j <= reach; ++j)
    for (int i = -reach; i <= reach; ++i) {
      const double x = i * scene.dx, y = j * scene.dx, r = std::hypot(x, y);
      if (r >= w.support()) continue;
      n += w.w(r);
      if (r > 0) virial += w.dw(r) / r * x * x;
    }
  return -virial / (scene.dx * scene.dx * n * n);
}

}  // namespace closurelab
