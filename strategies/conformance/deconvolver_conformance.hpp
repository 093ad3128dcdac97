#pragma once
// The deconvolver conformance checks (DESIGN.md §2) as a library, without GoogleTest, so that a user's project
// checks its own registered deconvolver exactly as the in-tree suite (tests/conformance/) checks the built-ins:
//
//   closurelab::Registry r;
//   closurelab::register_builtin_strategies(r);
//   r.deconvolvers.add(...);                       // the user's strategy
//   const auto report = closurelab::run_deconvolver_conformance(r, "richardson");
//   std::cout << report.to_string();               // one line per check, the failures with their reasons
//   return report.ok() ? 0 : 1;
//
// The checks (each by name): schema_is_complete_and_defaults_resolve, fixed_solve_is_finite_consistent_and_repeatable,
// scan_reports_true_residuals_and_stops_when_asked, discrepancy_principle_meets_tau_delta_or_says_so,
// rectangular_operator_is_handled_or_refused_clearly, bad_data_is_a_config_error,
// every_rule_beats_the_do_nothing_answer_clearly.
#include <string>
#include <vector>

#include "core/base/registry.hpp"
#include "strategies/conformance/conformance_report.hpp"

namespace closurelab {

// The names of every check, in the order they run.
const std::vector<std::string>& deconvolver_conformance_checks();

// Runs every check (or only `check`, one of deconvolver_conformance_checks()) on the deconvolver registered as
// `name` in `registry`. An unknown name or check is a ConfigError; an exception escaping a check is a failure.
ConformanceReport run_deconvolver_conformance(const Registry& registry, const std::string& name,
                                              const std::string& check = "");

}  // namespace closurelab
