#pragma once
// The scene conformance checks (DESIGN.md §5) as a library without GoogleTest, run by
// tests/conformance/test_strategy_conformance.cpp on every registered scene and by a user's project on its own.
// The scene is built from {"name": NAME, ...params}. A scene without an analytic solution passes the solution's
// checks vacuously.
//
// The checks (each by name), derivatives by central differences at two steps with the Richardson estimate of
// their truncation error as part of the tolerance (a wrong solution converges to the wrong value, the estimate
// does not hide it):
//   analytic_solution_satisfies_its_ode: d/dy(μ(y) dv/dy) + ρ f_x(y) = 0 away from walls and interfaces;
//   interfaces_carry_continuous_velocity_and_shear_stress: v and μ dv/dy continuous across each interface;
//   wall_conditions_hold: v = 0 on and beyond the wall surfaces; without walls, v and dv/dy periodic in y;
//   analytic_peak_is_the_maximum: analytic_peak is max |v| (relative 1e-5, the scene samples 2001 heights),
//     and a steady sine mode, where declared, is the solution.
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "strategies/conformance/conformance_report.hpp"

namespace closurelab {

const std::vector<std::string>& scene_conformance_checks();

// Runs every check (or only `check`) on the scene registered as `name` with parameters `params` (defaults for
// the rest). An unknown name or check, or parameters the scene refuses, is a ConfigError.
ConformanceReport run_scene_conformance(const Registry& registry, const std::string& name,
                                        const json& params = json::object(), const std::string& check = "");

}  // namespace closurelab
