#pragma once
// What every conformance library (deconvolvers, kernels, quadratures, scenes; strategies/conformance/) reports,
// and the GoogleTest-free expectations and check loop they share.
#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/base/errors.hpp"

namespace closurelab {

struct ConformanceFailure {
  std::string check;
  std::string message;
};

struct ConformanceReport {
  std::string name;                         // the strategy checked
  std::vector<std::string> checks;          // the checks run
  std::vector<ConformanceFailure> failures; // empty: it conforms
  bool ok() const { return failures.empty(); }
  std::string to_string() const;            // one line per check ("ok" or its failures), newline-terminated
};

namespace conformance {

// Records the failed expectations of one check (a GoogleTest-free EXPECT).
class Expect {
 public:
  Expect(std::string check, std::vector<ConformanceFailure>& out) : check_(std::move(check)), out_(out) {}
  bool that(bool condition, const std::string& what) {
    if (!condition) out_.push_back({check_, what});
    return condition;
  }
  bool near(double a, double b, double tolerance, const std::string& what) {
    std::ostringstream s;
    s.precision(17);
    s << what << ": " << a << " vs " << b << " (tolerance " << tolerance << ")";
    return that(std::abs(a - b) <= tolerance, s.str());  // false for NaN
  }
  template <class F>
  bool throws_config_error(F&& f, const std::string& what) {
    try {
      f();
    } catch (const ConfigError&) {
      return true;
    } catch (const std::exception& e) {
      return that(false, what + ": threw " + e.what() + " instead of a ConfigError");
    }
    return that(false, what + ": no ConfigError thrown");
  }

 private:
  std::string check_;
  std::vector<ConformanceFailure>& out_;
};

// The names of `checks`, in order.
template <class Check>
std::vector<std::string> check_names(const std::vector<std::pair<std::string, Check>>& checks) {
  std::vector<std::string> v;
  for (const auto& c : checks) v.push_back(c.first);
  return v;
}

// Runs every check of `checks` (or only `only`) on `subject`; an unknown check name is a ConfigError, an
// exception escaping a check is that check's failure.
template <class Subject, class Check>
ConformanceReport run_checks(const std::string& name, const Subject& subject,
                             const std::vector<std::pair<std::string, Check>>& checks, const std::string& only) {
  const auto names = check_names(checks);
  if (!only.empty() && std::find(names.begin(), names.end(), only) == names.end()) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    throw ConfigError("", "unknown conformance check '" + only + "'; known: " + known);
  }
  ConformanceReport report;
  report.name = name;
  for (const auto& [check_name, f] : checks) {
    if (!only.empty() && check_name != only) continue;
    report.checks.push_back(check_name);
    Expect e(check_name, report.failures);
    try {
      f(subject, e);
    } catch (const std::exception& err) {
      e.that(false, std::string("unexpected exception: ") + err.what());
    }
  }
  return report;
}

}  // namespace conformance
}  // namespace closurelab
