#pragma once
// The particle system, structure of arrays: position, velocity, mass, phase, held-fixed flag (2.1)–(2.3).
#include <cmath>
#include <cstdint>
#include <vector>

namespace closurelab {

struct PeriodicBox {
  double lx = 1.0, ly = 1.0;
  bool periodic_x = true, periodic_y = false;

  // Minimum-image displacement along each axis.
  double wrap_dx(double dx) const { return periodic_x ? dx - lx * std::nearbyint(dx / lx) : dx; }
  double wrap_dy(double dy) const { return periodic_y ? dy - ly * std::nearbyint(dy / ly) : dy; }
};

struct ParticleSystem {
  std::vector<double> x, y, vx, vy, mass;
  std::vector<int> phase;
  std::vector<std::uint8_t> fixed;  // 1: held in place at its prescribed velocity (wall particles, (5.3); 0 unless a lid)

  std::size_t size() const { return x.size(); }
  void add(double px, double py, double m, int ph, bool is_fixed) {
    x.push_back(px);
    y.push_back(py);
    vx.push_back(0.0);
    vy.push_back(0.0);
    mass.push_back(m);
    phase.push_back(ph);
    fixed.push_back(is_fixed ? 1 : 0);
  }
};

}  // namespace closurelab
