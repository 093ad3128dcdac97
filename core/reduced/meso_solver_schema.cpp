// The reduced model's solver section: schema and reader (declared in meso_solver.hpp).
#include "core/reduced/meso_solver.hpp"

#include "core/base/errors.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/sph/sph_run.hpp"

namespace closurelab {

ParamSchema meso_solver_schema() {
  const MesoSolverOptions d;  // the defaults
  ParamSchema schema{
      number_param("kappa", d.kappa, "time-step coefficient of (5.21)-(5.22)", 0.0, 1.0, true),
      number_param("spacing_over_eta", d.spacing_over_eta, "coarse mesh spacing / eta' (paper: 1)", 0.05, 4.0),
      string_param("scheme", name_of(d.scheme), "paper: (5.11)-(5.14); staggered: conservative flux form",
                   names_of<MesoScheme>()),
      bool_param("wall_constraint_forces", d.wall_constraint_forces,
                 "add the averaged constraint forces holding the wall particles (DESIGN.md par. 6)"),
      string_param("wall_node_value", name_of(d.wall_node_value),
                   "reported v at the wall-surface nodes: imposed (5.6) zero, or reconstructed (the average of the "
                   "closure's reconstruction there; an output only)",
                   names_of<WallNodeValue>()),
      string_param("balance", name_of(d.balance),
                   "right-hand side: stress_divergence (the paper: finite difference of the quadrature's T_int) or "
                   "force_density (exact divergence of (2.13): the averaged pair forces on the fluid particles, "
                   "wall constraint forces included; the quadrature is then unused)",
                   names_of<MesoBalance>()),
      string_param("time_integration", "explicit",
                   "the registered integrator (closurelab list integrator): explicit (forward Euler, the paper) or "
                   "backward_euler (implicit; needs a closure with fixed parameters, whose rate is affine in v)")};
  for (auto& p : time_loop_schema(d)) schema.push_back(std::move(p));
  return schema;
}

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

std::unique_ptr<Integrator> make_integrator(const Registry& registry, const json& resolved_solver,
                                            const std::string& path) {
  const std::string name = resolved_solver.at("time_integration").get<std::string>();
  if (!registry.integrators.contains(name))
    throw ConfigError(path + "/solver/time_integration",
                      "unknown integrator '" + name + "'; known: " + registry.integrators.known_names());
  return registry.integrators.create(json{{"name", name}}, path + "/solver/time_integration");
}

void check_implicit_closure(const json& solver, const Integrator& integrator, const json& deconvolver,
                            const std::string& path) {
  if (!integrator.needs_affine_rate()) return;
  // An integrator for an affine rate (backward Euler's Jacobian, probed once) is right only when the closure is
  // linear in v̄. A parameter rule is served by the two-pass rule (experiments/kinds/reduced_model.cpp: the parameter
  // chosen once from the steady state at the configured fixed one, then fixed); a Krylov method's iterate is not
  // linear at any count.
  const std::string name = deconvolver.value("name", "");
  const std::string integrator_name = solver.at("time_integration").get<std::string>();
  if (name == "cg" || name == "cgls")
    throw ConfigError(path + "/solver/time_integration",
                      integrator_name + " needs a closure linear in the coarse velocity (landweber, landweber_relaxed, "
                      "tikhonov or tsvd, a rule chosen by the two-pass rule); " + closure_nonlinearity(deconvolver) +
                          " (/closure/deconvolver); use time_integration explicit");
}

void check_meso_run(const Scene& scene, const AveragingKernel& kernel, const json& solver, const MesoSolverOptions& o,
                    const std::string& path) {
  const double h = reduced_grid(scene, kernel, o).coarse.spacing;
  check_stepped_run(scene, solver, h, coarse_time_step(o.kappa, scene.rho0, h, scene.max_viscosity(), 0.0), path);
}

MesoSolverOptions meso_options_from(const json& s) {
  MesoSolverOptions o;
  o.kappa = s.at("kappa").get<double>();
  o.spacing_over_eta = s.at("spacing_over_eta").get<double>();
  o.scheme = parse_name<MesoScheme>(s.at("scheme").get<std::string>(), "/solver/scheme");
  o.wall_constraint_forces = s.at("wall_constraint_forces").get<bool>();
  o.wall_node_value = parse_name<WallNodeValue>(s.at("wall_node_value").get<std::string>(), "/solver/wall_node_value");
  o.balance = parse_name<MesoBalance>(s.at("balance").get<std::string>(), "/solver/balance");
  read_time_loop(s, o);
  return o;
}

}  // namespace closurelab
