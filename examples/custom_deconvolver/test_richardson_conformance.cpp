// The Richardson iteration passes closurelab's deconvolver conformance checks (the same ones the in-tree suite
// runs on every built-in). Prints one line per check; exit 0 when all pass.
#include <iostream>

#include "richardson.hpp"
#include "strategies/conformance/deconvolver_conformance.hpp"

int main() {
  closurelab::Registry registry;
  closurelab::register_builtin_strategies(registry);
  closurelab_example::register_richardson(registry);
  const closurelab::ConformanceReport report = closurelab::run_deconvolver_conformance(registry, "richardson");
  std::cout << report.to_string();
  return report.ok() ? 0 : 1;
}
