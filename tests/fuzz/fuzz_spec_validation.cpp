// libFuzzer target: an experiment spec from arbitrary bytes goes through what `closurelab run` does before it
// runs anything (guarded parse, matrix expansion, the kind's validation of every cell). Anything but a clean
// ConfigError (a crash, a sanitizer report, another exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/base/errors.hpp"
#include "core/base/json_reader.hpp"
#include "core/base/registry.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/runner.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace closurelab;
  try {
    const json spec = parse_json_guarded(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
    const auto cells = expand_matrix(spec);
    if (cells.size() > 64) return 0;  // validating thousands of cells is slow, not wrong
    const ExperimentKind& kind = builtin_registry().experiments.get(spec.at("kind").get<std::string>(), "/kind");
    for (const auto& c : cells) kind.resolve(c.config, c.path, builtin_registry());
  } catch (const ConfigError&) {
  }
  return 0;
}
