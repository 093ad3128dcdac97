#pragma once
// Backward Euler (the integrator a solver section's time_integration names) probes the rate's Jacobian once, which
// is right only for a closure linear in v̄. Checked when a spec is validated, before anything runs (defined with the
// solver's schema, meso_solver_schema.cpp).
#include <memory>
#include <string>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "core/reduced/integrator.hpp"

namespace closurelab {

// A solver section's time_integration as given (a name, or {"name": ..., parameters}) checked against `registry`
// and resolved: the name alone for an entry without parameters (explicit, backward_euler: as specs wrote it before
// integrators took parameters), else the object with every parameter (defaults filled). ConfigError at `path` (the
// time_integration's JSON path; /name for an object's unknown name, the parameter's path for a bad parameter).
json resolve_time_integration(const Registry& registry, const json& given, const std::string& path);
// The integrator's name in a resolved solver section.
std::string integrator_name(const json& resolved_solver);
// The integrator a resolved solver section's time_integration names, from `registry`; an unknown name or a bad
// parameter is a ConfigError at `path`/solver/time_integration listing the known ones.
std::unique_ptr<Integrator> make_integrator(const Registry& registry, const json& resolved_solver,
                                            const std::string& path);
// With an integrator that needs an affine rate (backward_euler), cg/cgls is a ConfigError at
// `path`/solver/time_integration naming the deconvolver (a parameter rule is served by the two-pass rule,
// core/reduced/closure_rule.hpp: chosen once from the steady state reached at the configured fixed parameter).
// Why a resolved deconvolver is not linear in its data (a parameter rule, or cg/cgls), or "" when it is (the
// built-in linear ones with fixed parameters: landweber, landweber_relaxed, tikhonov, tsvd; a user-registered
// deconvolver is taken as linear).
std::string closure_nonlinearity(const json& resolved_deconvolver);
void check_implicit_closure(const json& resolved_solver, const Integrator& integrator, const json& resolved_deconvolver,
                            const std::string& path);

}  // namespace closurelab
