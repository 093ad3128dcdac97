#pragma once
// The deconvolution strategy family (DESIGN.md §2). Placeholder interface: the deconvolution issue
// defines it fully (forward operators, setup/solve, status and statistics).
#include <string>

namespace closurelab {

class Deconvolver {
 public:
  virtual ~Deconvolver() = default;
  virtual std::string name() const = 0;
};

}  // namespace closurelab
