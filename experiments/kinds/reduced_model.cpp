// Experiment kind "reduced_model": reduced model vs references, errors and cost in one row (a parameter rule under
// backward Euler by the two-pass rule, core/reduced/closure_rule.hpp; the sections and the row's ending shared with the 2D kinds are
// reduced_sections.cpp, the reference's averaging and the reference file reference_profiles.cpp).
// One file a little above the project's 320-line guide: it is one kind's resolve and run, whose steps (reference,
// oracles, the one or two passes, the transient, the row) share the resolved cell; what other kinds share is out.
#include "experiments/kinds/reduced_model.hpp"

#include <cmath>
#include <optional>
#include <tuple>

#include "core/scenes/analytic.hpp"
#include "core/averaging/averaging.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/base/errors.hpp"
#include "core/reduced/closure_rule.hpp"
#include "core/reduced/implicit_closure.hpp"
#include "core/reduced/meso_solver.hpp"
#include "core/base/metrics.hpp"
#include "core/sph/sph_run.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "experiments/kinds/cell_config.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/reduced_sections.hpp"
#include "experiments/kinds/reference_profiles.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

namespace {

ParamSchema oracle_schema() {
  return {bool_param("closure", false,
                     "closure oracle: reconstruction R(v) + (V_d - R(v_d)) with V_d the direct SPH particle velocity"),
          string_param("boundary", "none", "boundary oracle: hold the wall-surface nodes or the whole wall band at "
                                           "the averaged direct SPH",
                       names_of<BoundaryOracle>()),
          string_param("positions", "lattice",
                       "the particle positions the force-density balance's map, density and force are probed on: the "
                       "lattice, or the direct SPH's final particles (direct: the sheared lattice; force_density only)",
                       {"lattice", "direct"})};
}

using DirectProfiles = ReferenceProfiles;
class ReducedModel : public ExperimentKind {
 public:
  std::string name() const override { return "reduced_model"; }
  std::string description() const override {
    return "coarse solver with a deconvolution closure and a stress quadrature vs analytic, averaged analytic and "
           "averaged direct SPH (or a particle file from elsewhere in its place: reference.file), with cost and speed-up";
  }

  std::vector<KindSection> sections() const override {
    return {{"scene", "the scene (required)", "scene", {}},
            {"kernel", "the averaging kernel; its eta must equal the scene's", "kernel", {}},
            {"closure", "the deconvolution closure", "", closure_section<MesoSolverOptions>().schema()},
            {"quadrature", "the stress quadrature (default exact)", "quadrature", {}},
            {"solver", "the coarse solver", "", meso_solver_schema()},
            {"reference", "the direct SPH reference, or a particle file in its place", "", reference_with_file_schema()},
            {"transient", "snapshots of both solvers", "", transient_schema()},
            {"oracle", "oracle substitution from the direct SPH (the error budget)", "", oracle_schema()},
            {"timing", "how the reduced run is repeated for its time (minimum, median, spread)", "",
             reduced_timing_schema()}};
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    check_keys(cell, path,
               {"scene", "kernel", "closure", "quadrature", "solver", "reference", "transient", "oracle", "timing"});
    json out;
    auto scene = build_scene(cell, path, reg, &out["scene"]);
    if (!scene->x_invariant)
      throw ConfigError(path + "/scene",
                        "scene '" + scene->name + "' is not x-invariant; the coarse solver handles x-invariant scenes only");
    if (!scene->analytic_vx) throw ConfigError(path + "/scene", "scene '" + scene->name + "' has no analytic solution");
    auto kernel = build_kernel(cell, path, reg, scene->eta, &out["kernel"]);
    out["closure"] = resolve_section(cell, "closure", closure_section<MesoSolverOptions>().schema(), path);
    out["closure"]["deconvolver"] = reg.deconvolvers.resolve(out["closure"]["deconvolver"], path + "/closure/deconvolver");
    out["quadrature"] = reg.quadratures.resolve(cell.value("quadrature", json{{"name", "exact"}}), path + "/quadrature");
    out["solver"] = resolve_section(cell, "solver", meso_solver_schema(), path);
    out["solver"]["time_integration"] =
        resolve_time_integration(reg, out["solver"]["time_integration"], path + "/solver/time_integration");
    check_time_loop(out["solver"], path + "/solver");
    check_implicit_closure(out["solver"], *make_integrator(reg, out["solver"], path), out["closure"]["deconvolver"], path);
    out["reference"] = resolve_section(cell, "reference", reference_with_file_schema(), path);
    out["reference"]["solver"] =
        resolve_params(out["reference"]["solver"], sph_solver_schema(), path + "/reference/solver", {});
    check_time_loop(out["reference"]["solver"], path + "/reference/solver");
    if (out["reference"]["direct_sph"].get<bool>()) check_direct_run(*scene, out["reference"]["solver"], path + "/reference/solver");
    out["transient"] = resolve_transient(cell, path);
    out["oracle"] = resolve_section(cell, "oracle", oracle_schema(), path);
    out["timing"] = resolve_section(cell, "timing", reduced_timing_schema(), path);
    if (uses_oracles(out) && !out["reference"]["direct_sph"].get<bool>())
      throw ConfigError(path + "/oracle", "an oracle needs the direct SPH reference (reference.direct_sph = true)");
    if (out["oracle"]["positions"] == "direct" && out["solver"]["balance"] != "force_density")
      throw ConfigError(path + "/oracle/positions",
                        "the positions oracle re-probes the force-density balance's map: it needs solver.balance = "
                        "force_density");
    if (out["oracle"]["boundary"] != "none" && !scene->has_walls)
      throw ConfigError(path + "/oracle/boundary", "scene '" + scene->name + "' has no walls");
    check_reference_file(cell, out, *scene, path);  // reference_profiles.hpp
    // Cheap structural checks now (coarse mesh, quadrature fit) so that a bad cell fails before any runs; the
    // strategies are set up once, when the cell runs.
    try {
      check_meso_solver(*scene, *kernel, *reg.quadratures.create(out["quadrature"], "/quadrature"), options(out));
      check_meso_run(*scene, *kernel, out["solver"], options(out), "/solver");
    } catch (const ConfigError& e) {
      throw ConfigError(path + e.path(), e.message());
    }
    {  // the operator's shape (make_averaging_operator_1d): data x data, data x fine rows, or fine x fine
      const ReducedGrid grid = reduced_grid(*scene, *kernel, options(out));
      const Discretization disc = options(out).discretization;
      const long rows = disc == Discretization::fine_fine ? grid.fine.count : grid.data.count;
      const long cols = disc == Discretization::coarse_coarse ? grid.data.count : grid.fine.count;
      check_operator_shape(out["closure"], rows, cols, path);
      // k is used with rule fixed, and as pass 1 of the two-pass rule (a rule under an implicit integrator).
      const json& deconvolver = out["closure"]["deconvolver"];
      const bool fixed = deconvolver.value("rule", "fixed") == "fixed";
      if (fixed || make_integrator(reg, out["solver"], path)->needs_linear_closure())
        check_truncation_rank(deconvolver, rows, cols,
                              "data x unknowns of the " + out["closure"]["discretization"].get<std::string>() +
                                  " discretization",
                              !fixed, path);
    }
    return out;
  }

  // Rows stored before reference.file, the transient's one vocabulary (t_star, now t_over_tau), timing.min_seconds,
  // oracle.positions (the lattice, as they ran).
  json upgraded_params(json stored) const override {
    json out = upgraded_reduced_params(with_reference_file_defaults(ExperimentKind::upgraded_params(std::move(stored))));
    if (out.is_object() && out.contains("oracle") && out["oracle"].is_object() && !out["oracle"].contains("positions"))
      out["oracle"]["positions"] = "lattice";
    return out;
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    const auto scene = reg.scenes.create(cfg.at("scene"), "/scene");
    const auto kernel = reg.kernels.create(cfg.at("kernel"), "/kernel");
    MesoSolverOptions opt = options(cfg);
    opt.progress = progress;
    opt.snapshot_times = transient_times(cfg.at("transient"), *scene);
    // The direct reference first: the oracles need it before the reduced run.
    // A file's particles are averaged as a run's final state is; the run's snapshots at the transient's times.
    const double observe = cfg.at("reference").at("observe_spacing_over_eta").get<double>() * scene->eta;
    const std::optional<CellReference> ref =
        cell_reference(cfg, *scene, *kernel, column_mesh(scene->box, observe).y.spacing, opt.snapshot_times, progress);
    std::optional<DirectProfiles> direct;
    if (ref) {
      const Eigen::VectorXd nodes = reduced_grid(*scene, *kernel, opt).coarse.nodes();
      direct = reference_profiles(ref->particles, *scene, *kernel, nodes);
      if (!ref->from_file) direct->run = ref->record;
      for (const auto& snap : ref->snapshots) direct->snapshots.push_back(average_on_nodes(snap.particles, *scene, *kernel, nodes));
    }
    std::optional<MesoOracles> oracles;
    if (uses_oracles(cfg)) {
      MesoOracles o;
      o.closure = cfg.at("oracle").at("closure").get<bool>();
      o.boundary = parse_name<BoundaryOracle>(cfg.at("oracle").at("boundary").get<std::string>(), "/oracle/boundary");
      o.averaged = direct->averaged;
      o.row_y = direct->row_y;
      o.row_velocity = direct->row_velocity;
      if (cfg.at("oracle").at("positions") == "direct") o.positions = direct->particles;
      oracles = o;
    }
    // The reduced run, repeated until its fastest time is stable (timing section): the strategies and the
    // solver are built anew each time (setup: operators, factorizations, quadrature tables), and every run must
    // give the same numbers as the first.
    MesoResult reduced;
    std::vector<std::pair<double, Eigen::VectorXd>> reduced_snapshots;
    bool repeats_identical = true;
    int run_count = 0;
    // The two-pass rule (core/reduced/closure_rule.hpp): backward Euler needs a closure linear in v̄, so a
    // parameter rule under it is chosen once from pass 1's steady data and fixed for pass 2.
    ClosureParameterRule rule(reg, cfg.at("closure").at("deconvolver"),
                              make_integrator(reg, cfg.at("solver"), "")->needs_linear_closure(), opt.noise_level);
    // The column model and the strategies it holds by reference, built for one pass.
    struct ColumnModel {
      std::unique_ptr<Deconvolver> deconvolver;
      std::unique_ptr<StressQuadrature> quadrature;
      std::unique_ptr<Integrator> integrator;
      std::optional<MesoSolver> solver;
      MesoResult run() { return solver->run(); }
    };
    const RepeatedReducedRuns timing = repeat_reduced_run(
        [&] {
          std::vector<std::pair<double, Eigen::VectorXd>> snapshots;
          const auto build = [&](ClosurePass pass) {
            auto m = std::make_unique<ColumnModel>();
            m->deconvolver = rule.deconvolver(pass);
            m->quadrature = reg.quadratures.create(cfg.at("quadrature"), "/quadrature");
            m->integrator = make_integrator(reg, cfg.at("solver"), "");
            MesoSolverOptions o = opt;
            if (run_count > 0) o.progress = nullptr;  // progress lines from the first run only
            if (pass == ClosurePass::first)
              o.snapshot_times.clear();
            else
              o.on_snapshot = [&](double t, const Eigen::VectorXd& v) { snapshots.emplace_back(t, v); };
            m->solver.emplace(*scene, *kernel, *m->deconvolver, *m->quadrature, *m->integrator, o);
            if (oracles) m->solver->set_oracles(*oracles);
            return m;
          };
          auto passes = run_two_pass(rule, build, [&](ColumnModel& first, const MesoResult& r1) {
            rule.record()["pass_1_steps"] = r1.steps;
            rule.choose(first.solver->forward_operator(), first.solver->deconvolution_data());
          });
          MesoResult& r = passes.result;
          if (run_count++ > 0) repeats_identical = repeats_identical && r.v == reduced.v && r.steps == reduced.steps;
          reduced = std::move(r);
          reduced_snapshots = std::move(snapshots);
          return ReducedRunSeconds{passes.setup_seconds, passes.loop_seconds};
        },
        timing_policy_from(cfg.at("timing")));

    json row;
    row["status"] = row_status(reduced.status);
    row["reduced_model"] = reduced.to_json();
    if (rule.two_pass()) row["reduced_model"]["two_pass_rule"] = rule.record();
    const int nn = static_cast<int>(reduced.y.size());
    const double l1 = scene->wall_lo, l2 = scene->wall_hi, peak = scene->analytic_peak;
    const bool walls = scene->has_walls;
    Eigen::VectorXd analytic(nn), analytic_avg(nn);
    std::vector<bool> interior(nn), band(nn), fluid(nn), every(nn, true);
    const double r = kernel->support_radius();
    for (int n = 0; n < nn; ++n) {
      const double y = reduced.y[n];
      analytic[n] = scene->analytic_vx(y);
      analytic_avg[n] = average_by_quadrature(scene->analytic_vx, [&](double t) { return kernel->factor(t); }, r, y,
                                              walls ? l1 : y - r, walls ? l2 : y + r, scene->interfaces);
      fluid[n] = scene->in_fluid(y);
      interior[n] = scene->in_interior(y);
      band[n] = scene->in_wall_band(y);
    }
    auto norms = [&](const Eigen::VectorXd& ref) {
      return json{{"all_nodes", error_norms(reduced.v, ref, every, peak).to_json()},
                  {"fluid_nodes", error_norms(reduced.v, ref, fluid, peak).to_json()},
                  {"interior", error_norms(reduced.v, ref, interior, peak).to_json()},
                  {"wall_band", error_norms(reduced.v, ref, band, peak).to_json()},
                  {"peak_relative_difference", peak_relative_difference(reduced.v, ref)}};
    };
    json errors = {{"vs_analytic", norms(analytic)}, {"vs_averaged_analytic", norms(analytic_avg)}};
    if (const auto& mode = scene->steady_sine_mode) {
      // The steady sine amplitude against the true one, and the Landweber prediction e/(1 − (1 − e)^{n+1}) with
      // e the kernel's symbol at the mode (for the Gaussian, exp(−k²η'²/4)).
      double s = 0, norm = 0;
      for (int n = 0; n < nn; ++n) {
        s += reduced.v[n] * std::sin(mode->wavenumber * reduced.y[n]);
        norm += std::pow(std::sin(mode->wavenumber * reduced.y[n]), 2);
      }
      const double e = kernel->factor_symbol(mode->wavenumber / (2 * M_PI));
      errors["kolmogorov"] = {{"amplitude_ratio", s / norm / mode->amplitude}, {"e", e}};
      const json& d = cfg.at("closure").at("deconvolver");
      if (d.at("name") == "landweber" && d.at("rule") == "fixed")
        errors["kolmogorov"]["landweber_prediction"] = e / (1 - std::pow(1 - e, d.at("order").get<int>() + 1));
    }
    json profile = {{"y", reduced.y}, {"reduced", reduced.v}, {"analytic", analytic}, {"analytic_average", analytic_avg}};
    json cost = {{"steps", reduced.steps},
                 {"dt", reduced.dt},
                 {"model_time", reduced.time},
                 {"deconvolution_seconds", reduced.deconvolution_seconds},
                 {"deconvolution_matvecs", reduced.deconvolution_matvecs},
                 {"quadrature_seconds", reduced.quadrature_seconds},
                 {"pair_forces_per_step", reduced.quadrature_cost.evaluations > 0
                                              ? static_cast<double>(reduced.quadrature_cost.pair_forces) /
                                                    reduced.quadrature_cost.evaluations
                                              : 0.0},
                 {"bond_weights", reduced.quadrature_cost.bond_weights}};

    if (direct) {
      const Eigen::VectorXd& averaged = direct->averaged;
      const json& run = direct->run;
      const std::vector<Eigen::VectorXd>& direct_snapshots = direct->snapshots;
      errors["vs_averaged_direct_sph"] = norms(averaged);
      profile["direct_average"] = averaged;
      ref->record_into(row);
      // The transient: both runs at the same model times t = (t / τ) τ.
      json transient = json::array();
      const json& t_over_tau = cfg.at("transient").at("t_over_tau");
      for (std::size_t k = 0; k < t_over_tau.size(); ++k) {
        json snap = {{"t_over_tau", t_over_tau[k]}, {"time", opt.snapshot_times[k]}};
        // A run that reached steady state before this time stays there: its final state stands in.
        const bool reduced_has = k < reduced_snapshots.size() || reduced.status == Status::converged;
        const bool direct_has = k < direct_snapshots.size() || run.at("status") == "converged";
        if (reduced_has && direct_has) {
          const Eigen::VectorXd& vr = k < reduced_snapshots.size() ? reduced_snapshots[k].second : reduced.v;
          const Eigen::VectorXd& vd = k < direct_snapshots.size() ? direct_snapshots[k] : averaged;
          if (k >= reduced_snapshots.size() || k >= direct_snapshots.size()) snap["steady_state_stands_in"] = true;
          snap["vs_averaged_direct_sph"] = {{"all_nodes", error_norms(vr, vd, every, peak).to_json()},
                                            {"fluid_nodes", error_norms(vr, vd, fluid, peak).to_json()},
                                            {"peak_relative_difference", peak_relative_difference(vr, vd)}};
          snap["reduced"] = vr;
          snap["direct_average"] = vd;
        } else {
          snap["status"] = "not reached (a run ended before this time)";
        }
        transient.push_back(snap);
      }
      if (!t_over_tau.empty()) row["transient"] = transient;
    }
    finish_reduced_row(row, std::move(errors), std::move(cost), timing, repeats_identical, reduced.deconvolution_issues,
                       ref ? ref->timed_run() : nullptr);
    if (ref && ref->from_file) mark_untimed_reference(row);  // no direct run was timed: no speed-up (null, not 0)
    row["profile"] = profile;
    return row;
  }

 private:
  static bool uses_oracles(const json& cfg) {
    return cfg.at("oracle").at("closure").get<bool>() || cfg.at("oracle").at("boundary") != "none" ||
           cfg.at("oracle").at("positions") != "lattice";
  }

  static MesoSolverOptions options(const json& cfg) {
    MesoSolverOptions o = meso_options_from(cfg.at("solver"));
    closure_section<MesoSolverOptions>().read_into(cfg.at("closure"), o);
    return o;
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_reduced_model_experiment() { return std::make_unique<ReducedModel>(); }

}  // namespace closurelab
