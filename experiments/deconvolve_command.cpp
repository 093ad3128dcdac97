#include "experiments/deconvolve_command.hpp"

#include <iostream>

namespace closurelab {
int run_deconvolve_command(int, char**) {
  std::cerr << "closurelab deconvolve: not implemented yet\n";
  return 2;
}
}  // namespace closurelab
