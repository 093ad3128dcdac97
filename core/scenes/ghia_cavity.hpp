#pragma once
// The lid-driven cavity's reference: the steady centre-line velocities of Ghia, Ghia & Shin, "High-Re solutions for
// incompressible flow using the Navier-Stokes equations and a multigrid method", J. Comput. Phys. 48 (1982)
// 387–411, Table I (u along the vertical centre line x = L/2) and Table II (v along the horizontal one y = L/2), in
// units of the lid speed and the side, at Re = 100, 400 and 1000 (a 129 × 129 multigrid solution). The values are
// the paper's, as PySPH 1.0b1 ships them (pysph/examples/ghia_cavity_data.py).
#include <array>
#include <optional>

namespace closurelab {

struct GhiaCentrelines {
  static constexpr int kPoints = 17;
  double reynolds = 0.0;
  std::array<double, kPoints> y{}, u{};  // u(x = 1/2, y), Table I
  std::array<double, kPoints> x{}, v{};  // v(x, y = 1/2), Table II
};

// The tables at `reynolds` (100, 400 or 1000, exactly); none at any other Reynolds number.
inline std::optional<GhiaCentrelines> ghia_centrelines(double reynolds) {
  static constexpr std::array<double, GhiaCentrelines::kPoints> y = {
      1.0000, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5000,
      0.4531, 0.2813, 0.1719, 0.1016, 0.0703, 0.0625, 0.0547, 0.0000};
  static constexpr std::array<double, GhiaCentrelines::kPoints> x = {
      1.0000, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5000,
      0.2344, 0.2266, 0.1563, 0.0938, 0.0781, 0.0703, 0.0625, 0.0000};
  struct Column {
    double re;
    std::array<double, GhiaCentrelines::kPoints> u, v;
  };
  static constexpr std::array<Column, 3> columns = {{
      {100.0,
       {1.00000, 0.84123, 0.78871, 0.73722, 0.68717, 0.23151, 0.00332, -0.13641, -0.20581, -0.21090, -0.15662,
        -0.10150, -0.06434, -0.04775, -0.04192, -0.03717, 0.00000},
       {0.00000, -0.05906, -0.07391, -0.08864, -0.10313, -0.16914, -0.22445, -0.24533, 0.05454, 0.17527, 0.17507,
        0.16077, 0.12317, 0.10890, 0.10091, 0.09233, 0.00000}},
      {400.0,
       {1.00000, 0.75837, 0.68439, 0.61756, 0.55892, 0.29093, 0.16256, 0.02135, -0.11477, -0.17119, -0.32726,
        -0.24299, -0.14612, -0.10338, -0.09266, -0.08186, 0.00000},
       {0.00000, -0.12146, -0.15663, -0.19254, -0.22847, -0.23827, -0.44993, -0.38598, 0.05188, 0.30174, 0.30203,
        0.28124, 0.22965, 0.20920, 0.19713, 0.18360, 0.00000}},
      {1000.0,
       {1.00000, 0.65928, 0.57492, 0.51117, 0.46604, 0.33304, 0.18719, 0.05702, -0.06080, -0.10648, -0.27805,
        -0.38289, -0.29730, -0.22220, -0.20196, -0.18109, 0.00000},
       {0.00000, -0.21388, -0.27669, -0.33714, -0.39188, -0.51550, -0.42665, -0.31966, 0.02526, 0.32235, 0.33075,
        0.37095, 0.32627, 0.30353, 0.29012, 0.27485, 0.00000}},
  }};
  for (const Column& c : columns)
    if (c.re == reynolds) return GhiaCentrelines{reynolds, y, c.u, x, c.v};
  return std::nullopt;
}

}  // namespace closurelab
