#pragma once
// The stress-quadrature conformance checks (DESIGN.md §2) as a library without GoogleTest, run by
// tests/conformance/test_strategy_conformance.cpp on every registered quadrature and by a user's project on its
// own (as for deconvolvers: strategies/conformance/deconvolver_conformance.hpp shows how).
//
// `finest` holds the parameters (besides "name") of the quadrature's finest setting, the one that must be the
// exact pair sum (2.13): {} for a quadrature exact at its defaults, {"stride_x": 1, "stride_y": 1} for the coarse
// quadrature (5.27). The reference is independent of every quadrature: the averaging operator's interaction
// stress (core/averaging/averaging.hpp) of the SPH engine's pair forces.
//
// The checks (each by name):
//   finest_setting_is_the_exact_pair_sum: on a walled channel (both wall models), a general x-dependent field,
//     all four components;
//   virial_identity_on_a_periodic_box: at the finest setting, ∫ T_int over a periodic box = Σ f_jk ⊗ (q_k − q_j);
//   affine_in_velocity_and_blind_to_translation: at the default and the finest setting T(a u + b w) − T(0) =
//     a (T(u) − T(0)) + b (T(w) − T(0)) (positions are fixed, the viscous force is linear in v: the implicit
//     coarse solver relies on it); on a periodic box, T(v + c) = T(v) (the pair force sees differences only);
//   reports_each_call: evaluate() returns status converged and its own cost on a smooth field, and
//     numerical_issue with a message on a non-finite one (the outcome policy of core/closure/stress_quadrature.hpp).
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "strategies/conformance/conformance_report.hpp"

namespace closurelab {

// The names of every check, in the order they run.
const std::vector<std::string>& quadrature_conformance_checks();

// Runs every check (or only `check`) on the quadrature registered as `name`, whose finest setting is `finest`.
// An unknown name or check is a ConfigError; an exception escaping a check is a failure.
ConformanceReport run_quadrature_conformance(const Registry& registry, const std::string& name,
                                             const json& finest = json::object(), const std::string& check = "");

}  // namespace closurelab
