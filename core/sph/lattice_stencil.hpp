#pragma once
// The SPH pair stencil of the square lattice: for the models that read the pair forces of particles on their sites
// (the 2D force-density model, the direct SPH's linearised steady state).
#include <cmath>
#include <vector>

#include "core/sph/sph_kernel.hpp"

namespace closurelab {

// One neighbour of a lattice site, (di, dj) sites away, with F = w'(r)/r and q_ab = q_a − q_b = −(di, dj) dx.
struct LatticeOffset {
  int di, dj;
  double F, qx, qy;
};

// The offsets within the smoothing function's support on the lattice of spacing dx; n0 = Σ w (self included), the
// lattice's summation number density.
inline std::vector<LatticeOffset> lattice_pair_stencil(const SmoothingKernel& w, double dx, double& n0) {
  std::vector<LatticeOffset> stencil;
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

}  // namespace closurelab
