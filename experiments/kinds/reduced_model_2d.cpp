// Experiment kind "reduced_model_2d": the two-dimensional reduced model (core/reduced/meso_solver_2d.hpp) on a
// cellular scene, against the exact velocity A(t) · mode, its Gaussian average and the averaged direct SPH of
// the same box, with the closure's Landweber prediction, the transient, and the cost and speed-up; or in the
// lid-driven cavity (no exact field) against the averaged direct SPH alone, over all nodes and the interior ones
// (≥ 3η' from the walls), at the final and the saved times.
#include "experiments/kinds/reduced_model_2d.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/metrics.hpp"
#include "core/reduced/closure_rule.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/continuum/continuum_navier_stokes_2d.hpp"
#include "core/scenes/analytic.hpp"
#include "experiments/kinds/coarse_continuum_scoring.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/node_fields.hpp"
#include "experiments/kinds/reduced_sections.hpp"
#include "experiments/kinds/cell_config.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

namespace {

// A vector field at the nodes of a mesh, flat j * nx + i.
using Field = NodeVelocity;

Field mode_field(const TensorMesh2D& mesh, const Scene::CellularMode& mode, double amplitude) {
  Field f{Eigen::VectorXd(mesh.size()), Eigen::VectorXd(mesh.size())};
  const double k = mode.wavenumber, s = mode.offset;
  for (int n = 0; n < mesh.size(); ++n) {
    const Vec2 v = amplitude * cellular_mode(mesh.node(n).x() + s, mesh.node(n).y() + s, k);
    f.x[n] = v.x();
    f.y[n] = v.y();
  }
  return f;
}

// A cellular scene's scores at the final time: the exact field and its average (each mode times the kernel's symbol
// at (k, k) / 2π), and the amplitude on the mode against the exact one with the Landweber prediction
// e / (1 − (1 − e)^{n+1}), e the kernel's symbol (continuum) and e_h the eigenvalue of the discrete operator at the mode.
void cellular_scores(const Scene& scene, const AveragingKernel& kernel, const json& cfg, const TensorMesh2D& mesh,
                     const MesoResult2D& reduced, std::optional<double> landweber_e_h, json& errors, json& fields) {
  const Scene::CellularMode& mode = *scene.cellular_mode;
  const double k = mode.wavenumber, scale = scene.analytic_peak;
  const Field unit = mode_field(mesh, mode, 1.0), reduced_field{reduced.vx, reduced.vy};
  const double e = kernel.symbol(Vec2(k, k) / (2.0 * M_PI));
  const Field exact = mode_field(mesh, mode, mode.amplitude(reduced.time)),
              averaged = mode_field(mesh, mode, e * mode.amplitude(reduced.time));
  errors["vs_analytic"] = norms(reduced_field, exact, scale);
  errors["vs_averaged_analytic"] = norms(reduced_field, averaged, scale);
  json amplitude = {{"ratio", fitted(reduced_field, unit) / mode.amplitude(reduced.time)}, {"e", e}};
  const json& d = cfg.at("closure").at("deconvolver");
  if (d.at("name") == "landweber" && d.at("rule") == "fixed") {
    const int order = d.at("order").get<int>();
    amplitude["landweber_prediction"] = e / (1 - std::pow(1 - e, order + 1));
    if (landweber_e_h) {
      const double eh = *landweber_e_h;
      amplitude["e_h"] = eh;
      amplitude["landweber_prediction_discrete"] = eh / (1 - std::pow(1 - eh, order + 1));
    }
  }
  errors["amplitude"] = amplitude;
  fields["averaged_analytic"] = field_json(averaged);
}

class ReducedModel2D : public ExperimentKind {
 public:
  std::string name() const override { return "reduced_model_2d"; }
  std::string description() const override {
    return "two-dimensional coarse solver (both velocity components, staggered stress divergence) with a "
           "deconvolution closure and a stress quadrature on a cellular scene, vs the exact field, its average "
           "and the averaged direct SPH, or in the lid-driven cavity (incompressible, coarse_fine) vs the averaged "
           "direct SPH over all and interior nodes, with cost and speed-up";
  }

  std::vector<KindSection> sections() const override {
    return {{"scene", "the scene (required; one with a cellular mode, or the lid-driven cavity)", "scene", {}},
            {"kernel", "the averaging kernel; its eta must equal the scene's", "kernel", {}},
            {"closure", "the deconvolution closure (both components, Kronecker operator)", "", closure_section<MesoSolver2DOptions>().schema()},
            {"quadrature", "the stress quadrature (default exact), one instance per face mesh", "quadrature", {}},
            {"solver", "the 2D coarse solver", "", meso_solver_2d_schema()},
            {"reference", "the direct SPH reference", "", reference_schema()},
            {"transient", "snapshots of both solvers", "", transient_schema()},
            {"timing", "how the reduced run is repeated for its time (minimum, median, spread)", "",
             reduced_timing_schema()}};
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    check_keys(cell, path, {"scene", "kernel", "closure", "quadrature", "solver", "reference", "transient", "timing"});
    json out;
    auto scene = build_scene(cell, path, reg, &out["scene"]);
    if (!scene->cellular_mode && !scene->cavity)
      throw ConfigError(path + "/scene", "scene '" + scene->name + "' has neither a cellular mode (the 2D model's exact "
                                                                    "solution) nor the cavity's walls; use the cellular, "
                                                                    "the taylor-green or the lid-driven-cavity scene");
    auto kernel = build_kernel(cell, path, reg, scene->eta, &out["kernel"]);
    out["closure"] = resolve_section(cell, "closure", closure_section<MesoSolver2DOptions>().schema(), path);
    out["closure"]["deconvolver"] = reg.deconvolvers.resolve(out["closure"]["deconvolver"], path + "/closure/deconvolver");
    out["quadrature"] = reg.quadratures.resolve(cell.value("quadrature", json{{"name", "exact"}}), path + "/quadrature");
    out["solver"] = resolve_section(cell, "solver", meso_solver_2d_schema(), path);
    check_time_loop(out["solver"], path + "/solver");
    out["solver"]["time_integration"] =
        resolve_time_integration(reg, out["solver"]["time_integration"], path + "/solver/time_integration");
    {  // the integrator: registered, and able to serve the closure and the equations
      const auto integrator = make_integrator(reg, out["solver"], path);
      const json& s = out["solver"];
      if (integrator->finds_steady_state())  // before check_implicit_closure, whose advice (mode steady) is the column's
        throw ConfigError(path + "/solver/time_integration",
                          integrator_name(s) + " finds a steady state without stepping; the 2D stepped model marches "
                                               "(transients): use a stepping integrator");
      check_implicit_closure(out["solver"], *integrator, out["closure"]["deconvolver"], path);
      // The two-pass rule chooses a parameter from a steady state (core/reduced/closure_rule.hpp); the stepped 2D
      // model's runs are transients, so it runs none, and a rule under an integrator that probes the rate's
      // Jacobian once would be applied at every solve of a closure taken as linear.
      if (ClosureParameterRule::applies(out["closure"]["deconvolver"], integrator->needs_linear_closure()))
        throw ConfigError(path + "/closure/deconvolver/rule",
                          integrator_name(s) + " needs a closure linear in the coarse velocity, and the 2D stepped "
                                               "model runs no two-pass rule (a transient has no steady state to "
                                               "choose the parameter from): use rule fixed, or an explicit or ARKODE "
                                               "integrator");
      const std::string equations = s.at("equations").get<std::string>();
      if (integrator->needs_affine_rate() &&
          (equations == "mass_momentum" || (equations == "incompressible" && s.at("transport").get<bool>())))
        throw ConfigError(path + "/solver/time_integration",
                          integrator_name(s) + " needs a rate affine in the coarse state; " +
                              equations + "'s is not (the convective flux" +
                              (equations == "mass_momentum" ? ", the pressure of the density, v = (rho v) / rho" : "") +
                              "): use an explicit integrator");
    }
    out["reference"] = resolve_section(cell, "reference", reference_schema(), path);
    out["reference"]["solver"] =
        resolve_params(out["reference"]["solver"], sph_solver_schema(), path + "/reference/solver", {});
    check_time_loop(out["reference"]["solver"], path + "/reference/solver");
    if (out["reference"]["direct_sph"].get<bool>())
      check_direct_run(*scene, out["reference"]["solver"], path + "/reference/solver");
    out["transient"] = resolve_transient(cell, path);
    out["timing"] = resolve_section(cell, "timing", reduced_timing_schema(), path);
    try {
      check_meso_solver_2d(*scene, *kernel, *reg.quadratures.create(out["quadrature"], "/quadrature"), options(out));
      check_meso_run_2d(*scene, *kernel, out["solver"], options(out), "/solver");
    } catch (const ConfigError& e) {
      throw ConfigError(path + e.path(), e.message());
    }
    {  // the operator's shape (make_averaging_operator_2d): the coarse mesh's data, the coarse or lattice unknowns
      const TensorMesh2D coarse = continuum_mesh_for(*scene, *kernel, options(out).spacing_over_eta);
      const Discretization disc = options(out).discretization;
      const long side = scene->cavity ? std::lround(scene->cavity->side / scene->dx) : 0;  // the fluid's lattice
      const long lattice = scene->cavity ? side * side : static_cast<long>(scene->nx) * scene->ny,
                 data = coarse.nx() * static_cast<long>(coarse.ny());
      const long rows = disc == Discretization::fine_fine ? lattice : data,
                 cols = disc == Discretization::coarse_coarse ? data : lattice;
      check_operator_shape(out["closure"], rows, cols, path);
      // k is used with rule fixed (a rule chooses its own, and runs no two-pass rule here: refused above).
      if (out["closure"]["deconvolver"].value("rule", "fixed") == "fixed")
        check_truncation_rank(out["closure"]["deconvolver"], rows, cols,
                              "data x unknowns of the " + out["closure"]["discretization"].get<std::string>() +
                                  " discretization",
                              false, path);
      check_prior_on_2d_operator(out["closure"]["deconvolver"], path);
    }
    return out;
  }

  // Rows stored before timing.min_seconds and the solver's equations, transport, coarse_pressure and
  // time_integration existed (the linear model under forward Euler, as computed).
  json upgraded_params(json stored) const override {
    stored = upgraded_reduced_params(ExperimentKind::upgraded_params(std::move(stored)));
    if (stored.is_object() && stored.contains("solver") && stored["solver"].is_object()) {
      json& s = stored["solver"];
      const json defaults = {
          {"equations", "momentum"}, {"transport", true}, {"coarse_pressure", true}, {"time_integration", "explicit"}};
      for (const auto& [key, value] : defaults.items())
        if (!s.contains(key)) s[key] = value;
    }
    return stored;
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    const auto scene = reg.scenes.create(cfg.at("scene"), "/scene");
    const auto kernel = reg.kernels.create(cfg.at("kernel"), "/kernel");
    const double scale = scene->analytic_peak, tau = scene->time_scale();
    MesoSolver2DOptions opt = options(cfg);
    opt.progress = progress;
    opt.snapshot_times = transient_times(cfg.at("transient"), *scene);

    const std::optional<CellReference> direct =
        cell_reference(cfg, *scene, *kernel, cfg.at("reference").at("observe_spacing_over_eta").get<double>() * scene->eta,
                       opt.snapshot_times, progress);
    // The reduced run, repeated until its fastest time is stable (timing section), strategies and solver built
    // anew each time; every run must give the same numbers as the first.
    std::vector<std::pair<double, Field>> reduced_snapshots;
    MesoResult2D reduced;
    std::optional<double> landweber_e_h;  // the discrete operator's eigenvalue at the mode (coarse–coarse)
    bool repeats_identical = true;
    int run_count = 0;
    const RepeatedReducedRuns timing = repeat_reduced_run(
        [&] {
          auto deconv = reg.deconvolvers.create(cfg.at("closure").at("deconvolver"), "/closure/deconvolver");
          auto on_x_faces = reg.quadratures.create(cfg.at("quadrature"), "/quadrature");
          auto on_y_faces = reg.quadratures.create(cfg.at("quadrature"), "/quadrature");
          auto integrator = make_integrator(reg, cfg.at("solver"), "");
          std::vector<std::pair<double, Field>> snapshots;
          MesoSolver2DOptions o = opt;
          if (run_count > 0) o.progress = nullptr;  // progress lines from the first run only
          o.on_snapshot = [&](double t, const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) {
            snapshots.push_back({t, Field{vx, vy}});
          };
          const auto t_setup = std::chrono::steady_clock::now();
          MesoSolver2D solver(*scene, *kernel, *deconv, *on_x_faces, *on_y_faces, *integrator, o);
          // The average (2.9) of the lattice's initial velocities, the walls' particles at theirs (the cavity's lid).
          if (scene->initial_velocity || scene->cavity) {
            const MesoFields f =
                average_particles(scene->make_particles(), scene->box, *kernel, solver.coarse_mesh(), AveragingRequest{});
            solver.set_velocity(f.vx, f.vy);
          }
          const double setup = seconds_since(t_setup);
          MesoResult2D r = solver.run();
          if (run_count++ > 0)
            repeats_identical = repeats_identical && r.vx == reduced.vx && r.vy == reduced.vy && r.steps == reduced.steps;
          else {
            if (opt.discretization == Discretization::coarse_coarse && scene->cellular_mode) {
              const Eigen::VectorXd m = mode_field(solver.coarse_mesh(), *scene->cellular_mode, 1.0).x;
              landweber_e_h = m.dot(solver.forward_operator().apply(m)) / m.squaredNorm();
            }
          }
          reduced = std::move(r);
          reduced_snapshots = std::move(snapshots);
          return ReducedRunSeconds{setup, reduced.wall_seconds};
        },
        timing_policy_from(cfg.at("timing")));
    const TensorMesh2D& mesh = reduced.mesh;
    const Field reduced_field{reduced.vx, reduced.vy};
    json errors = json::object(), fields = {{"x", mesh.x.nodes()}, {"y", mesh.y.nodes()}, {"reduced", field_json(reduced_field)}};
    if (scene->cellular_mode) cellular_scores(*scene, *kernel, cfg, mesh, reduced, landweber_e_h, errors, fields);
    // The cavity's nodes ≥ 3η' from the walls (none elsewhere: every node is then reported once, as all_nodes).
    const std::vector<int> interior = interior_nodes(*scene, mesh);

    const long evaluations = reduced.quadrature_cost.evaluations;
    json cost = {{"steps", reduced.steps},
                 {"dt", reduced.dt},
                 {"model_time", reduced.time},
                 {"coarse_nodes", mesh.size()},
                 {"deconvolution_seconds", reduced.deconvolution_seconds},
                 {"deconvolution_matvecs", reduced.deconvolution_matvecs},
                 {"quadrature_seconds", reduced.quadrature_seconds},
                 {"quadrature_setup_seconds", reduced.quadrature_cost.setup_seconds},
                 // both face meshes: two evaluations per step
                 {"pair_forces_per_step",
                  evaluations > 0 ? 2.0 * static_cast<double>(reduced.quadrature_cost.pair_forces) / evaluations : 0.0},
                 {"bond_weights", reduced.quadrature_cost.bond_weights}};
    json row;
    row["status"] = row_status(reduced.status);
    row["reduced_model"] = reduced.to_json();
    if (direct) {
      const auto average_of = [&](const ParticleSystem& ps) {
        const MesoFields f = average_particles(ps, scene->box, *kernel, mesh, AveragingRequest{});
        return Field{f.vx, f.vy};
      };
      const Field direct_field = average_of(direct->particles);
      const double direct_time = direct->record.at("time").get<double>();
      errors["vs_averaged_direct_sph"] = norms(reduced_field, direct_field, scale, interior);
      // A cellular scene's mode at unit amplitude and the averaged exact field at time t (the kernel's symbol e).
      const Scene::CellularMode* mode = scene->cellular_mode ? &*scene->cellular_mode : nullptr;
      const double e = mode ? kernel->symbol(Vec2(mode->wavenumber, mode->wavenumber) / (2.0 * M_PI)) : 0.0;
      const auto averaged_exact = [&](double t) { return mode_field(mesh, *mode, e * mode->amplitude(t)); };
      // The reference's own error: the averaged direct SPH against the averaged exact field at its final time.
      if (mode) errors["direct_sph_vs_averaged_analytic"] = norms(direct_field, averaged_exact(direct_time), scale);
      fields["direct_average"] = field_json(direct_field);
      direct->record_into(row);
      json transient = json::array();
      for (std::size_t s = 0; s < opt.snapshot_times.size(); ++s) {
        const double t = opt.snapshot_times[s];
        json snap = {{"t_over_tau", t / tau}, {"time", t}};
        if (s < reduced_snapshots.size() && s < direct->snapshots.size()) {
          const Field& r = reduced_snapshots[s].second;
          const Field dsnap = average_of(direct->snapshots[s].particles);
          snap["reduced_vs_averaged_direct_sph"] = norms(r, dsnap, scale, interior);
          // The same against the averaged direct field's own peak at this time (a decaying flow's errors relative
          // to what is left of it, not to the initial peak `scale`).
          snap["reduced_vs_averaged_direct_sph_at_its_peak"] = norms(r, dsnap, speed(dsnap).maxCoeff(), interior);
          if (mode) {
            const Field avg_exact = averaged_exact(t), unit = mode_field(mesh, *mode, 1.0);
            snap["reduced_vs_averaged_analytic"] = norms(r, avg_exact, scale);
            snap["direct_sph_vs_averaged_analytic"] = norms(dsnap, avg_exact, scale);
            snap["amplitude"] = {{"reduced", fitted(r, unit)},
                                 {"direct_sph_average", fitted(dsnap, unit)},
                                 {"averaged_analytic", e * mode->amplitude(t)}};
          }
        } else {
          snap["status"] = "not reached (a run ended before this time)";
        }
        transient.push_back(snap);
      }
      if (!transient.empty()) row["transient"] = transient;
    }
    finish_reduced_row(row, std::move(errors), std::move(cost), timing, repeats_identical, reduced.deconvolution_issues,
                       direct ? direct->timed_run() : nullptr);
    row["fields"] = fields;
    return row;
  }

  // The direct reference dominates: particles n² times steps ~ n²; without it, the coarse quadrature's grid.
  double expected_cost(const json& cfg) const override {
    const double n = cfg.at("scene").value("n", 48);
    return cfg.at("reference").at("direct_sph").get<bool>() ? n * n * n * n : n * n;
  }

 private:
  static MesoSolver2DOptions options(const json& cfg) {
    MesoSolver2DOptions o = meso_2d_options_from(cfg.at("solver"));
    closure_section<MesoSolver2DOptions>().read_into(cfg.at("closure"), o);
    return o;
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_reduced_model_2d_experiment() { return std::make_unique<ReducedModel2D>(); }

}  // namespace closurelab
