#pragma once
// The pair passes of the direct SPH engine (core/sph/sph_engine.*) over its Verlet list grouped by particle:
// the density pass (a block's kernel values in one vectorized loop, then the row sums) and the force pass (5.1)
// (a row's force on its particle summed in registers, its opposite scattered to the partners). Internal to the
// engine: the loops read raw arrays that do not alias.
#include <cstddef>
#include <cstdint>

#include "core/sph/particles.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_pair_force.hpp"

// Further compilations of the density kernel loop for AVX2 and AVX-512, chosen at run time (PairKernelIsa), where
// the baseline lacks them.
#if defined(__x86_64__) && !defined(__AVX2__)
#define CLOSURELAB_AVX2_CLONE 1
#else
#define CLOSURELAB_AVX2_CLONE 0
#endif
#if defined(__x86_64__) && !defined(__AVX512F__)
#define CLOSURELAB_AVX512_CLONE 1
#else
#define CLOSURELAB_AVX512_CLONE 0
#endif

namespace closurelab {

// The Verlet list as the passes read it: pairs (i, j), i < j, grouped by i into rows (j ascending), rows into
// blocks of about 256 pairs, the unit of the passes and of their threads.
struct PairBlocks {
  const std::int32_t *pi, *pj;  // the listed pairs, grouped by i
  const std::int32_t* row_i;    // row r: particle i of the listed pairs [row_begin[r], row_begin[r + 1])
  const std::uint32_t* row_begin;
  const std::uint32_t* block_row;  // block b: rows [block_row[b], block_row[b + 1])
};

namespace pair_passes {

// Minimum image along a periodic axis, d − L rint(d/L), with rint as the round-to-nearest shift by 1.5·2⁵²
// (exact for |d/L| < 2⁵¹) and 1/L precomputed: no library call in the pair loop. For the listed pairs
// (|d| far from L/2) it equals PeriodicBox::wrap_dx bitwise. With 1/L = 0 (an axis that is not periodic) it
// returns d unchanged: no branch.
inline double wrap(double d, double len, double inv_len) {
  constexpr double shift = 6755399441055744.0;
  const double k = (d * inv_len + shift) - shift;
  return d - len * k;
}

// A block's listed pairs: q_i − q_j and w'/r per pair into the list's arrays, w into the block's scratch; no
// store to a particle, so the compiler vectorizes it (gathers of the positions; the square root, division and
// max of several pairs in one vector register).
template <SmoothingKernel::Type T>
inline void density_kernel(const SmoothingKernel kernel, double lx, double ly, double ilx, double ily,
                           const double* __restrict x, const double* __restrict y, const std::int32_t* __restrict pi,
                           const std::int32_t* __restrict pj, std::size_t len, double* __restrict qx,
                           double* __restrict qy, double* __restrict dw_over_r, double* __restrict w) {
#pragma omp simd
  for (std::size_t k = 0; k < len; ++k) {
    const int i = pi[k], j = pj[k];
    const double dx = wrap(x[i] - x[j], lx, ilx), dy = wrap(y[i] - y[j], ly, ily);
    qx[k] = dx;
    qy[k] = dy;
    kernel.w_and_dw_over_r<T>(dx * dx + dy * dy, w[k], dw_over_r[k]);
  }
}

#if CLOSURELAB_AVX2_CLONE
// The same loop compiled for AVX2 (four pairs per vector). AVX2 without FMA: every operation is rounded as in the
// baseline, so both give the same bits (test SphEngineVectorKernels).
template <SmoothingKernel::Type T>
[[gnu::target("avx2")]] void density_kernel_avx2(const SmoothingKernel kernel, double lx, double ly, double ilx,
                                                 double ily, const double* __restrict x, const double* __restrict y,
                                                 const std::int32_t* __restrict pi, const std::int32_t* __restrict pj,
                                                 std::size_t len, double* __restrict qx, double* __restrict qy,
                                                 double* __restrict dw_over_r, double* __restrict w) {
  density_kernel<T>(kernel, lx, ly, ilx, ily, x, y, pi, pj, len, qx, qy, dw_over_r, w);
}
#endif

#if CLOSURELAB_AVX512_CLONE
// The same loop compiled for AVX-512 (eight pairs per vector). AVX-512F implies FMA, so the file that instantiates
// it, sph_engine.cpp, is compiled with -ffp-contract=off (core/CMakeLists.txt): no product is fused into a sum and
// the bits are the baseline's (test SphEngineVectorKernels).
template <SmoothingKernel::Type T>
[[gnu::target("avx512f")]] void density_kernel_avx512(const SmoothingKernel kernel, double lx, double ly, double ilx,
                                                      double ily, const double* __restrict x,
                                                      const double* __restrict y, const std::int32_t* __restrict pi,
                                                      const std::int32_t* __restrict pj, std::size_t len,
                                                      double* __restrict qx, double* __restrict qy,
                                                      double* __restrict dw_over_r, double* __restrict w) {
  density_kernel<T>(kernel, lx, ly, ilx, ily, x, y, pi, pj, len, qx, qy, dw_over_r, w);
}
#endif

// The density pass over blocks [b0, b1): per block the kernel loop, then row by row w added to the densities in
// n: particle i's sum kept in a register over its row, only j's scattered (a pair-by-pair scatter chains through
// memory whenever consecutive pairs share a particle). Listed pairs beyond the support give w = w'/r = 0.
template <SmoothingKernel::Type T>
void density_blocks(const SmoothingKernel kernel, const PeriodicBox box, const double* __restrict x,
                    const double* __restrict y, const PairBlocks& g, std::size_t b0, std::size_t b1,
                    double* __restrict qx, double* __restrict qy, double* __restrict dw_over_r, double* __restrict w,
                    double* __restrict n, [[maybe_unused]] PairKernelIsa isa) {
  const double lx = box.lx, ly = box.ly;
  const double ilx = box.periodic_x ? 1.0 / lx : 0.0, ily = box.periodic_y ? 1.0 / ly : 0.0;
  for (std::size_t b = b0; b < b1; ++b) {
    const std::size_t r0 = g.block_row[b], r1 = g.block_row[b + 1];
    const std::size_t p0 = g.row_begin[r0], len = g.row_begin[r1] - p0;
#if CLOSURELAB_AVX512_CLONE
    if (isa == PairKernelIsa::avx512)
      density_kernel_avx512<T>(kernel, lx, ly, ilx, ily, x, y, g.pi + p0, g.pj + p0, len, qx + p0, qy + p0,
                               dw_over_r + p0, w);
    else
#endif
#if CLOSURELAB_AVX2_CLONE
    if (isa == PairKernelIsa::avx2)
      density_kernel_avx2<T>(kernel, lx, ly, ilx, ily, x, y, g.pi + p0, g.pj + p0, len, qx + p0, qy + p0,
                             dw_over_r + p0, w);
    else
#endif
      density_kernel<T>(kernel, lx, ly, ilx, ily, x, y, g.pi + p0, g.pj + p0, len, qx + p0, qy + p0, dw_over_r + p0, w);
    for (std::size_t r = r0; r < r1; ++r) {
      double sum = 0.0;
      for (std::size_t p = g.row_begin[r], e = g.row_begin[r + 1]; p < e; ++p) {
        sum += w[p - p0];
        n[g.pj[p]] += w[p - p0];
      }
      n[g.row_i[r]] += sum;
    }
  }
}

// Inputs of the force pass.
struct ForceInputs {
  const SphPairInput* s;
  const double* mu;
  const int* phase;
  PairViscosityMean mean;
  double unlike;     // added to P_i/n_i² + P_j/n_j² of an unlike pair: twice the excess of (7.1)
  double mu_single;  // μ_ij of a one-phase scene (2μ, as pair_viscosity gives for like particles)
};

// (5.1) for pair (i, j) with relative velocity v_i − v_j: the force on i. OnePhase: every pair is a like pair.
template <bool OnePhase>
inline void force_pair(const ForceInputs& in, int i, int j, double F, double qx, double qy, double& fx, double& fy) {
  const SphPairInput &a = in.s[i], &b = in.s[j];
  double p_sum = a.p_over_n2 + b.p_over_n2, mu_ij = in.mu_single;
  if constexpr (!OnePhase) {
    p_sum += in.phase[i] != in.phase[j] ? in.unlike : 0.0;
    mu_ij = pair_viscosity(in.mu[i], in.mu[j], in.mean);
  }
  sph_pair_force(p_sum, mu_ij * (a.inv_n * b.inv_n), F, qx, qy, a.vx - b.vx, a.vy - b.vy, fx, fy);
}

// The force pass over rows [r0, r1): the force on i of each listed pair from `pair` (i, j, p) -> (fx, fy), summed
// over the row in registers, its opposite added to each j. A listed pair beyond the support (F = w'/r = 0 from
// the density pass; on the lattice a third of the list, the skin's share) is skipped: its force is an exact zero, so
// the sums are the same bits, and the branch costs less than the pair.
template <class PairForceOnI>
void force_rows(const PairBlocks& g, std::size_t r0, std::size_t r1, const double* __restrict F, PairForceOnI pair,
                double* __restrict f) {
  for (std::size_t r = r0; r < r1; ++r) {
    const int i = g.row_i[r];
    double sx = 0.0, sy = 0.0;
    for (std::size_t p = g.row_begin[r], e = g.row_begin[r + 1]; p < e; ++p) {
      if (F[p] == 0.0) continue;
      const int j = g.pj[p];
      double fx, fy;
      pair(i, j, p, fx, fy);
      sx += fx;
      sy += fy;
      f[2 * j] -= fx;
      f[2 * j + 1] -= fy;
    }
    f[2 * i] += sx;
    f[2 * i + 1] += sy;
  }
}

// The force pass of the transport-velocity formulation (core/sph/transport_velocity.hpp) over rows [r0, r1): as
// force_rows, with four values per pair from `pair` (i, j, p) -> (fx, fy, bx, by), the momentum force and the
// background pressure's part, and four per particle in f.
template <class PairTerms>
void force_rows_with_background(const PairBlocks& g, std::size_t r0, std::size_t r1, const double* __restrict F,
                                PairTerms pair, double* __restrict f) {
  for (std::size_t r = r0; r < r1; ++r) {
    const int i = g.row_i[r];
    double sx = 0.0, sy = 0.0, tx = 0.0, ty = 0.0;
    for (std::size_t p = g.row_begin[r], e = g.row_begin[r + 1]; p < e; ++p) {
      if (F[p] == 0.0) continue;
      const int j = g.pj[p];
      double fx, fy, bx, by;
      pair(i, j, p, fx, fy, bx, by);
      sx += fx;
      sy += fy;
      tx += bx;
      ty += by;
      f[4 * j] -= fx;
      f[4 * j + 1] -= fy;
      f[4 * j + 2] -= bx;
      f[4 * j + 3] -= by;
    }
    f[4 * i] += sx;
    f[4 * i + 1] += sy;
    f[4 * i + 2] += tx;
    f[4 * i + 3] += ty;
  }
}

}  // namespace pair_passes
}  // namespace closurelab
