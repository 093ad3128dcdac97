// Experiment kind "reduced_model_2d_force_density": the linearised force-density reduced model in two dimensions
// with solids (core/reduced/force_density_2d.hpp) on a scene periodic in x, and in y or walled in y (the cylinder
// lattice, the channels as one column), against the
// averaged direct SPH of the same box at steady state (or a particle file in its place, reference.file:
// experiments/kinds/reference_profiles.hpp, averaged onto the coarse mesh by the same call), with the Darcy
// permeability beside the scene's reference, and the cost and speed-up (the reduced run repeated as the timing
// section says; no speed-up against a file).
#include <cmath>
#include <optional>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/metrics.hpp"
#include "core/base/option_table.hpp"
#include "core/reduced/closure_rule.hpp"
#include "core/reduced/force_density_2d.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/node_fields.hpp"
#include "experiments/kinds/permeability_validation.hpp"
#include "experiments/kinds/reduced_model_2d.hpp"
#include "experiments/kinds/reduced_sections.hpp"
#include "experiments/kinds/reference_profiles.hpp"
#include "experiments/kinds/cell_config.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

namespace {

// "closure", declared once: the deconvolver (created twice from the registry) and the noise level it reads.
const OptionTable<ForceDensity2DOptions>& force_density_closure_section() {
  using O = ForceDensity2DOptions;
  static const OptionTable<O> table =
      OptionTable<O>("/closure")
          .unbound(object_param("deconvolver", json{{"name", "tikhonov"}},
                                "registered deconvolver and its parameters (two instances: velocity and density deviation)"))
          .number("noise_level", &O::noise_level, "delta handed to the deconvolver's parameter rule", 0.0);
  return table;
}

class ReducedModelForceDensity2D : public ExperimentKind {
 public:
  std::string name() const override { return "reduced_model_2d_force_density"; }
  std::string description() const override {
    return "two-dimensional linearised force-density reduced model with solids (velocity and density deviation "
           "deconvolved, the exact averaged pair forces of the lattice, steady state by one linear solve, or marched from "
           "rest by a registered integrator) on a doubly "
           "periodic or walled scene (walls are solids; an x-invariant scene is one column), vs the averaged direct SPH, "
           "with the Darcy permeability where the scene has one, cost and speed-up";
  }

  std::vector<KindSection> sections() const override {
    return {{"scene", "the scene (required; periodic in x, periodic or walled in y, solids by position)", "scene", {}},
            {"kernel", "the averaging kernel; its eta must equal the scene's", "kernel", {}},
            {"closure", "the deconvolution closure (dense operators on the reconstruction mesh)", "",
             force_density_closure_section().schema()},
            {"solver", "the 2D force-density solver", "", force_density_2d_schema()},
            {"reference", "the direct SPH reference, or a particle file in its place", "", reference_with_file_schema()},
            {"timing", "how the reduced run is repeated for its time (minimum, median, spread)", "",
             reduced_timing_schema()}};
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    check_keys(cell, path, {"scene", "kernel", "closure", "solver", "reference", "timing"});
    json out;
    auto scene = build_scene(cell, path, reg, &out["scene"]);
    auto kernel = build_kernel(cell, path, reg, scene->eta, &out["kernel"]);
    out["closure"] = resolve_section(cell, "closure", force_density_closure_section().schema(), path);
    out["closure"]["deconvolver"] = reg.deconvolvers.resolve(out["closure"]["deconvolver"], path + "/closure/deconvolver");
    out["solver"] = resolve_section(cell, "solver", force_density_2d_schema(), path);
    check_time_loop(out["solver"], path + "/solver");
    out["solver"]["time_integration"] =
        resolve_time_integration(reg, out["solver"]["time_integration"], path + "/solver/time_integration");
    const bool marched = is_marched(out);
    {  // the integrator: newton (the model's steady solve, mode steady) or one that marches and serves the closure
      const auto integrator = make_integrator(reg, out["solver"], path);
      const json& s = out["solver"];
      const json& deconvolver = out["closure"]["deconvolver"];
      if (!marched && s.at("mode").get<std::string>() != "steady")
        throw ConfigError(path + "/solver/mode", "time_integration newton gives the steady state only: set mode to "
                                                 "steady, or march to a target time with a stepping integrator "
                                                 "(arkode_erk, arkode_imex, explicit, backward_euler)");
      if (marched) check_implicit_closure(s, *integrator, deconvolver, path);
      if (marched && ClosureParameterRule::applies(deconvolver, integrator->needs_linear_closure()))
        throw ConfigError(path + "/closure/deconvolver/rule",
                          integrator_name(s) + " needs a closure linear in the coarse state, and a marched run has "
                                               "no two-pass rule (it chooses from the steady state of the steady "
                                               "solve): use rule fixed, an ARKODE integrator, or time_integration "
                                               "newton");
      if (marched && integrator->needs_affine_rate() && s.at("convective_stress").get<bool>())
        throw ConfigError(path + "/solver/time_integration",
                          integrator_name(s) + " needs a rate affine in the coarse state; the convective flux is "
                                               "quadratic: use an ARKODE integrator, or time_integration newton");
    }
    out["reference"] = resolve_section(cell, "reference", reference_with_file_schema(), path);
    out["reference"]["solver"] =
        resolve_params(out["reference"]["solver"], sph_solver_schema(), path + "/reference/solver", {});
    check_time_loop(out["reference"]["solver"], path + "/reference/solver");
    if (out["reference"]["direct_sph"].get<bool>())
      check_direct_run(*scene, out["reference"]["solver"], path + "/reference/solver");
    out["timing"] = resolve_section(cell, "timing", reduced_timing_schema(), path);
    check_reference_file(cell, out, *scene, path);  // reference_profiles.hpp
    try {
      check_force_density_2d(*scene, *kernel, options(out));
      check_force_density_closure(out["closure"]["deconvolver"], "", !marched);
      // The operators are at most coarse nodes x reconstruction nodes (the free rows, the velocity's columns the
      // nodes some fluid particle reads); a rule's pass 1 runs at the configured k too.
      const ForceDensity2DOptions o = options(out);
      const TensorMesh2D coarse = force_density_coarse_mesh(*scene, *kernel, o.spacing_over_eta);
      const TensorMesh2D recon =
          force_density_reconstruction_mesh(*scene, coarse, o.reconstruction_refinement, o.reconstruction_y_nodes);
      check_truncation_rank(out["closure"]["deconvolver"], static_cast<long>(coarse.size()), static_cast<long>(recon.size()),
                            "coarse nodes x reconstruction nodes", out["closure"]["deconvolver"].value("rule", "fixed") != "fixed",
                            "");
      if (marched) {  // the loop's largest step: the signal speed is at least the sound speed
        const double h = coarse.nx() == 1 ? coarse.y.spacing : std::min(coarse.x.spacing, coarse.y.spacing);
        check_stepped_run(*scene, out["solver"], h,
                          coarse_time_step(o.kappa, scene->rho0, h, scene->max_viscosity(), scene->sound_speed),
                          "/solver");
      }
    } catch (const ConfigError& e) {
      throw ConfigError(path + e.path(), e.message());
    }
    if (out["reference"]["direct_sph"].get<bool>() && out["reference"]["file"].get<std::string>().empty())
      check_observe_mesh(*scene, out["reference"]["observe_spacing_over_eta"].get<double>() * scene->eta,
                         path + "/reference/observe_spacing_over_eta");
    return out;
  }

  // Rows stored before reference.file, timing.min_seconds, the solver's convective flux, reconstruction_y_nodes,
  // pair_forces and time_integration existed (those ran without the flux, on cell-centred reconstruction rows, with
  // the standard forces, to the steady state by the model's solve).
  json upgraded_params(json stored) const override {
    stored = upgraded_reduced_params(with_reference_file_defaults(ExperimentKind::upgraded_params(std::move(stored))));
    if (stored.is_object() && stored.contains("solver") && stored["solver"].is_object() &&
        !stored["solver"].contains("convective_stress")) {
      const ForceDensity2DOptions d;
      stored["solver"]["convective_stress"] = d.convective_stress;
      stored["solver"]["newton_tolerance"] = d.newton_tolerance;
      stored["solver"]["newton_max_iterations"] = d.newton_max_iterations;
    }
    if (stored.is_object() && stored.contains("solver") && stored["solver"].is_object() &&
        !stored["solver"].contains("reconstruction_y_nodes"))
      stored["solver"]["reconstruction_y_nodes"] = name_of(ReconstructionYNodes::cell_centred);
    if (stored.is_object() && stored.contains("solver") && stored["solver"].is_object() &&
        !stored["solver"].contains("pair_forces"))
      stored["solver"]["pair_forces"] = name_of(SphFormulation::standard);
    if (stored.is_object() && stored.contains("solver") && stored["solver"].is_object() &&
        !stored["solver"].contains("time_integration")) {  // the steady solve, before the model could march
      const ParamSchema schema = force_density_2d_schema();
      for (const char* key : {"time_integration", "kappa", "mode", "target_time", "steady_tolerance", "steady_window",
                              "max_time", "max_steps"})
        for (const ParamSpec& p : schema)
          if (p.name == key) stored["solver"][key] = p.default_value;
    }
    return stored;
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    const auto scene = reg.scenes.create(cfg.at("scene"), "/scene");
    const auto kernel = reg.kernels.create(cfg.at("kernel"), "/kernel");
    ForceDensity2DOptions opt = options(cfg);
    const bool marched = is_marched(cfg);
    opt.progress = progress;
    const std::optional<CellReference> ref =
        cell_reference(cfg, *scene, *kernel, cfg.at("reference").at("observe_spacing_over_eta").get<double>() * scene->eta,
                       {}, progress);
    ForceDensity2DResult reduced;
    bool repeats_identical = true;
    int run_count = 0;
    // The two-pass rule (core/reduced/closure_rule.hpp): the steady state is one linear solve, so a parameter rule
    // is chosen once from pass 1's steady data, each deconvolver from its own (v̄_x for the velocity, n̄ for the
    // density deviation), and fixed for pass 2.
    ClosureParameterRule rule(reg, cfg.at("closure").at("deconvolver"), !marched, opt.noise_level);
    // The model and the two deconvolvers and the integrator it holds by reference, built for one pass.
    struct ForceDensityModel {
      std::unique_ptr<Deconvolver> velocity, density;
      std::unique_ptr<Integrator> stepper;  // null: the steady solve
      std::optional<ForceDensitySolver2D> solver;
      ForceDensity2DResult run() { return solver->run(); }
    };
    const RepeatedReducedRuns timing = repeat_reduced_run(
        [&] {
          const auto build = [&](ClosurePass pass) {
            auto m = std::make_unique<ForceDensityModel>();
            m->velocity = rule.deconvolver(pass, "velocity");
            m->density = rule.deconvolver(pass, "density");
            if (marched) m->stepper = make_integrator(reg, cfg.at("solver"), "");
            m->solver.emplace(*scene, *kernel, *m->velocity, *m->density, opt, m->stepper.get());
            return m;
          };
          auto passes = run_two_pass(rule, build, [&](ForceDensityModel& first, const ForceDensity2DResult&) {
            rule.choose(first.solver->velocity_operator(), first.solver->free_vx(), "velocity");
            rule.choose(first.solver->density_operator(), first.solver->free_density(), "density");
          });
          ForceDensity2DResult& r = passes.result;
          if (run_count++ > 0)
            repeats_identical = repeats_identical && r.vx == reduced.vx && r.vy == reduced.vy && r.density == reduced.density;
          reduced = std::move(r);
          return ReducedRunSeconds{passes.setup_seconds, passes.loop_seconds};
        },
        timing_policy_from(cfg.at("timing")));
    const TensorMesh2D& mesh = reduced.mesh;
    std::vector<bool> outside(static_cast<std::size_t>(mesh.size()), true);
    for (int n = 0; n < mesh.size(); ++n) outside[static_cast<std::size_t>(n)] = !scene->is_solid(mesh.node(n).x(), mesh.node(n).y());
    const NodeVelocity reduced_field{reduced.vx, reduced.vy};
    // The cell's momentum per unit mass: Σ ρ̄ v̄ Δ² / (ρ0 L²) = ⟨u⟩ (the window integrates to one over the mesh).
    const Eigen::VectorXd rho_bar =
        average_particles(scene->make_particles(), scene->box, *kernel, mesh, AveragingRequest{}).rho;
    const double area = scene->box.lx * scene->box.ly;
    const auto momentum_mean = [&](const Eigen::VectorXd& vx) {
      return rho_bar.dot(vx) * mesh.cell_area() / (scene->rho0 * area);
    };
    json errors, row;
    const double mu = scene->phase_viscosity.at(0);
    std::optional<double> k_reduced;
    if (scene->permeability) {
      const Scene::Permeability& perm = *scene->permeability;
      const double to_k = mu / (scene->rho0 * perm.body_force);
      k_reduced = to_k * reduced.superficial_velocity;
      errors["permeability"] = {{"reduced", *k_reduced},
                                {"reduced_from_coarse_momentum", to_k * momentum_mean(reduced.vx)},
                                {"reference", perm.reference},
                                {"reduced_vs_reference", *k_reduced / perm.reference - 1.0}};
    }
    json fields = {{"x", mesh.x.nodes()}, {"y", mesh.y.nodes()}, {"reduced", field_json(reduced_field)},
                   {"outside_solid", outside}, {"reduced_density_deviation", reduced.density}};
    row["status"] = row_status(reduced.status);
    if (reduced.status != Status::converged && reduced.status != Status::target_time) row["message"] = reduced.message;
    row["reduced_model"] = reduced.to_json();
    if (rule.two_pass()) row["reduced_model"]["two_pass_rule"] = rule.record();
    // The reference's particles, the direct run's final state or the file's, averaged and scored alike.
    const ParticleSystem* reference = ref ? &ref->particles : nullptr;
    if (reference) {
      const MesoFields f = average_particles(*reference, scene->box, *kernel, mesh, AveragingRequest{});
      const NodeVelocity direct_field{f.vx, f.vy};
      const double scale = speed(direct_field).maxCoeff();
      errors["vs_averaged_direct_sph"] = norms(reduced_field, direct_field, scale, {}, outside);
      errors["scale_peak_speed_of_averaged_direct_sph"] = std::isfinite(scale) ? json(scale) : json(nullptr);
      if (!usable_scale(scale)) {  // the norms are null (metrics.hpp); the row says why
        const std::string why = "the reference's peak averaged speed is " +
                                std::string(scale == 0 ? "zero (a reference at rest)" : "not a finite positive number") +
                                ": no relative error against it (norms null)";
        row["message"] = row["status"] == "ok" ? why : row.value("message", std::string()) + "; " + why;
        row["status"] = "numerical_issue";
      }
      fields["direct_average"] = field_json(direct_field);
      ref->record_into(row);
      if (k_reduced) {
        const double k_direct = darcy_permeability(*scene, *reference);
        const double to_k = mu / (scene->rho0 * scene->permeability->body_force);
        errors["permeability"]["direct_sph"] = k_direct;
        errors["permeability"]["direct_sph_from_coarse_momentum"] = to_k * momentum_mean(direct_field.x);
        errors["permeability"]["reduced_vs_direct_sph"] = *k_reduced / k_direct - 1.0;
        errors["permeability"]["direct_sph_vs_reference"] = k_direct / scene->permeability->reference - 1.0;
      }
    }
    json cost = {{"coarse_nodes", mesh.size()},
                 {"free_nodes", reduced.free_nodes},
                 {"reconstruction_nodes", reduced.reconstruction_nodes},
                 {"assembly_and_deconvolver_setup_seconds", reduced.setup_seconds},
                 {"assembly_seconds", reduced.assembly_seconds},
                 {"probe_seconds", reduced.probe_seconds},
                 {"deconvolution_seconds", reduced.deconvolution_seconds},
                 {"deconvolution_matvecs", reduced.deconvolution_matvecs}};
    if (marched) {
      cost["steps"] = reduced.steps;
      cost["rate_evaluations"] = reduced.rate_evaluations;
    } else if (opt.convective_stress) {
      cost["newton_iterations"] = reduced.newton_iterations;
      cost["newton_seconds"] = reduced.newton_seconds;
      cost["newton_last_relative_step"] = reduced.newton_last_step;
    }
    finish_reduced_row(row, std::move(errors), std::move(cost), timing, repeats_identical, reduced.deconvolution_issues,
                       ref ? ref->timed_run() : nullptr);
    if (ref && ref->from_file) mark_untimed_reference(row);  // no direct run was timed: no speed-up (null, not 0)
    row["fields"] = fields;
    return row;
  }

  // The direct reference dominates: particles n² times steps ~ n² (none with a file in its place).
  double expected_cost(const json& cfg) const override {
    const double n = cfg.at("scene").value("n", 48);
    const bool runs_direct =
        cfg.at("reference").at("direct_sph").get<bool>() && cfg.at("reference").value("file", "").empty();
    return runs_direct ? n * n * n * n : n * n;
  }

 private:
  // Marched (a stepping integrator) or the steady solve (newton).
  static bool is_marched(const json& cfg) { return integrator_name(cfg.at("solver")) != "newton"; }
  static ForceDensity2DOptions options(const json& cfg) {
    ForceDensity2DOptions o = force_density_2d_options_from(cfg.at("solver"));
    force_density_closure_section().read_into(cfg.at("closure"), o);
    return o;
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_reduced_model_force_density_2d_experiment() {
  return std::make_unique<ReducedModelForceDensity2D>();
}

}  // namespace closurelab
