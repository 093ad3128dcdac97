#include "strategies/conformance/conformance_report.hpp"

namespace closurelab {

std::string ConformanceReport::to_string() const {
  std::string s;
  for (const auto& c : checks) {
    std::string lines;
    for (const auto& f : failures)
      if (f.check == c) lines += "    " + f.message + "\n";
    s += name + " " + c + ": " + (lines.empty() ? "ok\n" : "FAILED\n" + lines);
  }
  return s;
}

}  // namespace closurelab
