// Reference permeability of a periodic square array of cylinders: Hasimoto / Sangani–Acrivos series and a
// boundary-collocation Stokes solve of the cell (core/scenes/square_array_stokes.hpp).
#include "core/scenes/square_array_stokes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace closurelab {

double square_array_drag_series(double c) {
  if (!(c > 0.0)) throw std::invalid_argument("square_array_drag_series: the solid fraction must be positive");
  return 4.0 * M_PI / (-0.5 * std::log(c) - 0.738 + c - 0.887 * c * c + 2.038 * c * c * c);
}

namespace {

// f(r) and its first three r-derivatives, for psi = f(r) sin(n theta).
struct Radial {
  double f, f1, f2, f3;
};

// f = scale * sum_k coef_k (r/a)^p_k.
Radial powers(double r, double a, const std::vector<std::pair<double, double>>& terms, double scale) {
  Radial out{0, 0, 0, 0};
  const double rho = r / a;
  for (const auto& [coef, p] : terms) {
    const double v = coef * std::pow(rho, p) * scale;
    out.f += v;
    out.f1 += v * p / r;
    out.f2 += v * p * (p - 1.0) / (r * r);
    out.f3 += v * p * (p - 1.0) * (p - 2.0) / (r * r * r);
  }
  return out;
}

// The Stokeslet column, n = 1: f = r ln(r/a) − r/2 + a²/(2r) (r ln r plus the r and 1/r that make f(a) = f'(a) = 0).
Radial stokeslet(double r, double a) {
  return {r * std::log(r / a) - 0.5 * r + a * a / (2.0 * r), std::log(r / a) + 0.5 - a * a / (2.0 * r * r),
          1.0 / r + a * a / (r * r * r), -1.0 / (r * r) - 3.0 * a * a / (r * r * r * r)};
}

// What the boundary conditions read of psi = f(r) sin(n theta) at (x, y): psi, d psi/dx, the vorticity
// omega = −lap psi and d omega/dx.
struct Values {
  double psi, psi_x, omega, omega_x;
};
Values values(const Radial& f, int n, double x, double y) {
  const double r = std::hypot(x, y), th = std::atan2(y, x), c = x / r, s = y / r;
  const double sn = std::sin(n * th), cn = std::cos(n * th), n2 = static_cast<double>(n) * n;
  const double g = f.f2 + f.f1 / r - n2 * f.f / (r * r);  // lap psi = g(r) sin(n theta)
  const double g1 = f.f3 + f.f2 / r - f.f1 / (r * r) - n2 * f.f1 / (r * r) + 2.0 * n2 * f.f / (r * r * r);
  Values v;
  v.psi = f.f * sn;
  v.psi_x = c * f.f1 * sn - s / r * n * f.f * cn;
  v.omega = -g * sn;
  v.omega_x = -(c * g1 * sn - s / r * g * n * cn);
  return v;
}

}  // namespace

SquareArrayStokesResult square_array_stokes(double a_over_l, int modes) {
  if (!(a_over_l > 0.0 && a_over_l < 0.5)) throw std::invalid_argument("square_array_stokes: need 0 < a/L < 1/2");
  if (modes < 2) throw std::invalid_argument("square_array_stokes: need at least 2 modes");
  const double a = a_over_l, half = 0.5;  // L = 1
  const double rho_max = std::sqrt(0.5) / a;
  // Columns: 0: Q/2; 1: n = 1, r^3 combination; then for n = 3, 5, ...: the r^n and r^(n+2) combinations, each
  // scaled by its largest power at the cell corner so that every column is O(1) on the boundary.
  struct Column {
    int n;
    std::vector<std::pair<double, double>> terms;
    double scale;
  };
  std::vector<Column> cols;
  cols.push_back({1, {{1.0, 3.0}, {-2.0, 1.0}, {1.0, -1.0}}, std::pow(rho_max, -3.0)});
  for (int k = 1; k < modes; ++k) {
    const int n = 2 * k + 1;
    const double dn = n;
    cols.push_back({n, {{1.0, dn}, {dn - 1.0, -dn}, {-dn, 2.0 - dn}}, std::pow(rho_max, -dn)});
    cols.push_back({n, {{1.0, dn + 2.0}, {dn, -dn}, {-(dn + 1.0), 2.0 - dn}}, std::pow(rho_max, -dn - 2.0)});
  }
  const int unknowns = 1 + static_cast<int>(cols.size());
  const int per_edge = 4 * unknowns;
  Eigen::MatrixXd m(4 * per_edge, unknowns);
  Eigen::VectorXd rhs(4 * per_edge);
  int row = 0;
  for (int edge = 0; edge < 2; ++edge)
    for (int k = 0; k < per_edge; ++k) {
      const double t = half * (k + 0.5) / per_edge;
      const double x = edge == 0 ? t : half, y = edge == 0 ? half : t;  // edge 0: top (y = L/2); 1: right
      const Values st = values(stokeslet(std::hypot(x, y), a), 1, x, y);
      // Top: psi − Q/2 = 0 and omega = 0; right: psi_x = 0 and omega_x = 0. The Stokeslet's coefficient is 1.
      m(row, 0) = edge == 0 ? -1.0 : 0.0;
      m(row + 1, 0) = 0.0;
      rhs[row] = -(edge == 0 ? st.psi : st.psi_x);
      rhs[row + 1] = -(edge == 0 ? st.omega : st.omega_x);
      for (std::size_t j = 0; j < cols.size(); ++j) {
        const Values v = values(powers(std::hypot(x, y), a, cols[j].terms, cols[j].scale), cols[j].n, x, y);
        m(row, 1 + j) = edge == 0 ? v.psi : v.psi_x;
        m(row + 1, 1 + j) = edge == 0 ? v.omega : v.omega_x;
      }
      row += 2;
    }
  const Eigen::VectorXd sol = m.colPivHouseholderQr().solve(rhs);
  const double q = 2.0 * sol[0];  // the flux per unit width with F = 4 pi mu (Stokeslet coefficient 1)
  SquareArrayStokesResult res;
  res.modes = modes;
  res.drag = 4.0 * M_PI / q;
  res.permeability = 1.0 / res.drag;
  res.boundary_residual = (m * sol - rhs).cwiseAbs().maxCoeff() / std::abs(q);
  return res;
}

}  // namespace closurelab
