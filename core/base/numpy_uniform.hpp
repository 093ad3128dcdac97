#pragma once
// numpy's legacy uniform generator (numpy.random.seed(s); numpy.random.random(k)), reproduced bit for bit so that a
// scene can draw the same random numbers as a PySPH example run (e.g. taylor_green.py's --perturb): the Mersenne
// Twister MT19937 seeded by init_genrand(s) (std::mt19937(s); numpy's legacy seeding of an integer seed), each double
// from two 32-bit draws a, b as ((a >> 5) 2^26 + (b >> 6)) / 2^53 (numpy's mt19937_next_double), in [0, 1).
#include <cstdint>
#include <random>

namespace closurelab {

class NumpyLegacyUniform {
 public:
  explicit NumpyLegacyUniform(std::uint32_t seed) : mt_(seed) {}
  double next() {
    const std::uint32_t a = static_cast<std::uint32_t>(mt_()) >> 5, b = static_cast<std::uint32_t>(mt_()) >> 6;
    return (a * 67108864.0 + b) / 9007199254740992.0;
  }

 private:
  std::mt19937 mt_;
};

}  // namespace closurelab
