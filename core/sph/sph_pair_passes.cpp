// Which compilation of the density kernel loop the engine uses (PairKernelIsa): AVX-512, else AVX2, where the
// baseline build runs on a CPU that has it, unless a test or benchmark chose otherwise.
#include <atomic>
#include <stdexcept>
#include <string>

#include "core/sph/sph_pair_passes.hpp"

namespace closurelab {

namespace {

std::atomic<PairKernelIsa>& chosen_isa() {
  static std::atomic<PairKernelIsa> isa{[] {
#if CLOSURELAB_AVX512_CLONE
    if (__builtin_cpu_supports("avx512f")) return PairKernelIsa::avx512;
#endif
#if CLOSURELAB_AVX2_CLONE
    if (__builtin_cpu_supports("avx2")) return PairKernelIsa::avx2;
#endif
    return PairKernelIsa::baseline;
  }()};
  return isa;
}

}  // namespace

bool pair_kernel_isa_available(PairKernelIsa isa) {
#if CLOSURELAB_AVX512_CLONE
  if (isa == PairKernelIsa::avx512) return __builtin_cpu_supports("avx512f");
#else
  if (isa == PairKernelIsa::avx512) return false;
#endif
#if CLOSURELAB_AVX2_CLONE
  if (isa == PairKernelIsa::avx2) return __builtin_cpu_supports("avx2");
#else
  if (isa == PairKernelIsa::avx2) return false;
#endif
  return true;
}

PairKernelIsa pair_kernel_isa() { return chosen_isa().load(); }

void set_pair_kernel_isa(PairKernelIsa isa) {
  if (!pair_kernel_isa_available(isa))
    throw std::invalid_argument("set_pair_kernel_isa: this build or CPU has no " + name_of(isa) + " pair kernel");
  chosen_isa().store(isa);
}

}  // namespace closurelab
