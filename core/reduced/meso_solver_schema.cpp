// The reduced model's solver section: its options declared once, the schema and reader from them (declared in
// meso_solver.hpp).
#include "core/reduced/meso_solver.hpp"

#include "core/base/errors.hpp"
#include "core/base/option_table.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/sph/sph_run.hpp"

namespace closurelab {

namespace {

const OptionTable<MesoSolverOptions>& meso_solver_options() {
  using O = MesoSolverOptions;
  static const OptionTable<O> table =
      OptionTable<O>("/solver")
          .number("kappa", &O::kappa, "time-step coefficient of (5.21)-(5.22)", 0.0, 1.0, true)
          .number("spacing_over_eta", &O::spacing_over_eta, "coarse mesh spacing / eta' (paper: 1)", 0.05, 4.0)
          .choice("scheme", &O::scheme, "paper: (5.11)-(5.14); staggered: conservative flux form")
          .boolean("wall_constraint_forces", &O::wall_constraint_forces,
                   "add the averaged constraint forces holding the wall particles (DESIGN.md par. 6)")
          .choice("wall_node_value", &O::wall_node_value,
                  "reported v at the wall-surface nodes: imposed (5.6) zero, or reconstructed (the average of the "
                  "closure's reconstruction there; an output only)")
          .choice("balance", &O::balance,
                  "right-hand side: stress_divergence (the paper: finite difference of the quadrature's T_int) or "
                  "force_density (exact divergence of (2.13): the averaged pair forces on the fluid particles, "
                  "wall constraint forces included; the quadrature is then unused)")
          .unbound(entry_param(
              "time_integration", "explicit",
              "the registered integrator (closurelab list integrator), a name or {\"name\": ..., its parameters}: "
              "explicit (forward Euler, the paper), backward_euler (implicit; needs a closure with fixed "
              "parameters, whose rate is affine in v), arkode_erk (SUNDIALS adaptive explicit Runge-Kutta) or "
              "arkode_imex (SUNDIALS additive Runge-Kutta, implicit part by Newton-Krylov)"))
          .time_loop();
  return table;
}

}  // namespace

ParamSchema meso_solver_schema() { return meso_solver_options().schema(); }

std::string closure_nonlinearity(const json& deconvolver) {
  // A parameter rule picks its parameter from the data (GCV's choice moves with v̄: under the force-density
  // balance a backward-Euler probe happened to agree and a run reached 2.2x the analytic peak, "converged"), and a
  // Krylov method's iterate is a nonlinear function of the data whatever its count.
  const std::string name = deconvolver.value("name", "");
  const std::string rule = deconvolver.value("rule", "fixed");
  return name == "cg" || name == "cgls"
             ? "'" + name + "' is a Krylov method: its iterate is not linear in the data, so the rate is not affine in v"
         : rule != "fixed" ? "the parameter rule '" + rule + "' chooses the parameter from the data, so the closure is "
                             "not linear in v (use rule fixed)"
                           : "";
}

json resolve_time_integration(const Registry& registry, const json& given, const std::string& path) {
  const json config = given.is_string() ? json{{"name", given}} : given;
  if (!config.is_object() || !config.contains("name") || !config.at("name").is_string())
    throw ConfigError(path, "expected an integrator's name or an object with a string \"name\"; known: " +
                                registry.integrators.known_names());
  const std::string name = config.at("name").get<std::string>();
  if (!registry.integrators.contains(name))
    throw ConfigError(given.is_string() ? path : path + "/name",
                      "unknown integrator '" + name + "'; known: " + registry.integrators.known_names());
  json resolved = registry.integrators.resolve(config, path);
  // An entry without parameters stays its name: a spec that names one resolves as it did before integrators
  // took parameters (the stored rows and cell ids of explicit and backward_euler are unchanged).
  if (resolved.size() == 1) return name;
  return resolved;
}

std::string integrator_name(const json& resolved_solver) {
  const json& t = resolved_solver.at("time_integration");
  return t.is_string() ? t.get<std::string>() : t.at("name").get<std::string>();
}

std::unique_ptr<Integrator> make_integrator(const Registry& registry, const json& resolved_solver,
                                            const std::string& path) {
  const std::string at = path + "/solver/time_integration";
  const json resolved = resolve_time_integration(registry, resolved_solver.at("time_integration"), at);
  return registry.integrators.create(resolved.is_string() ? json{{"name", resolved}} : resolved, at);
}

void check_implicit_closure(const json& solver, const Integrator& integrator, const json& deconvolver,
                            const std::string& path) {
  if (integrator.finds_steady_state() && solver.value("mode", "") != "steady")
    throw ConfigError(path + "/solver/time_integration",
                      integrator_name(solver) + " finds the steady state and takes no time step: set mode to steady, "
                                                "or use a stepping integrator");
  if (!integrator.needs_linear_closure()) return;
  // An integrator for an affine rate (backward Euler's Jacobian, probed once) is right only when the closure is
  // linear in v̄. A parameter rule is served by the two-pass rule (core/reduced/closure_rule.hpp: the parameter
  // chosen once from the steady state at the configured fixed one, then fixed); a Krylov method's iterate is not
  // linear at any count.
  const std::string name = deconvolver.value("name", "");
  if (name == "cg" || name == "cgls")
    throw ConfigError(path + "/solver/time_integration",
                      integrator_name(solver) + " needs a closure linear in the coarse velocity (landweber, landweber_relaxed, "
                      "tikhonov or tsvd, a rule chosen by the two-pass rule); " + closure_nonlinearity(deconvolver) +
                          " (/closure/deconvolver); use an integrator that probes no Jacobian (explicit, arkode_erk, "
                          "arkode_imex with linear_solver gmres)");
}

void check_meso_run(const Scene& scene, const AveragingKernel& kernel, const json& solver, const MesoSolverOptions& o,
                    const std::string& path) {
  const double h = reduced_grid(scene, kernel, o).coarse.spacing;
  check_stepped_run(scene, solver, h, coarse_time_step(o.kappa, scene.rho0, h, scene.max_viscosity(), 0.0), path);
}

MesoSolverOptions meso_options_from(const json& s) { return meso_solver_options().read(s); }

}  // namespace closurelab
