// Experiment kind "coarse_continuum_2d": the coarse continuum Navier–Stokes baseline
// (core/continuum/continuum_navier_stokes_2d.hpp) on the 2D reduced model's own mesh (continuum_mesh_for at the same
// spacing_over_eta), scored as reduced_model_2d scores the reduced model: against the exact field, its average and
// the averaged direct SPH of the same box (the same reference store entry when the reference sections match), at
// the final time and at the transient's snapshots, with the same cost columns (setup and loop timed apart, the
// speed-up over the direct run). Scenes: doubly periodic, one phase, with an exact single-mode solution (the
// cellular scene, forced or a Taylor–Green start; the taylor-green scene), and the lid-driven cavity (walls, no exact
// field): there the baseline is also seen through the averaging (experiments/kinds/coarse_continuum_scoring.hpp) and
// its centre lines are compared with Ghia's.
#include "experiments/kinds/coarse_continuum.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/metrics.hpp"
#include "core/base/repeated_timing.hpp"
#include "core/base/time_loop.hpp"
#include "core/continuum/continuum_navier_stokes_2d.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/coarse_continuum_scoring.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/reduced_sections.hpp"
#include "experiments/kinds/cell_config.hpp"

namespace closurelab {

namespace {

using Field = NodeVelocity;

ParamSchema solver_schema() {
  const CoarseNavierStokes2DOptions d;
  return {
      number_param("spacing_over_eta", 1.0, "coarse mesh spacing / eta' (the 2D reduced model's mesh)", 0.05, 4.0),
      number_param("target_time", 1.0, "model time to march to", 0.0, {}, true),
      number_param("cfl", d.cfl, "time step <= cfl h / max|v| (central convection with AB2: <= 0.5)", 0.0, 1.0, true),
      number_param("viscous_number", d.viscous_number, "time step <= viscous_number h^2 / nu (AB2 in 2D: <= 1/8)", 0.0,
                   0.125, true),
      string_param("initial", "averaged",
                   "averaged: the average (2.9) of the lattice's initial velocities at the nodes (the reduced "
                   "model's start); sampled: the scene's initial velocity at the nodes",
                   {"averaged", "sampled"}),
      string_param("force", "averaged",
                   "averaged: the averaged body force (2.14)/(2.8) at the nodes (the reduced model's); sampled: the "
                   "scene's body force at the nodes",
                   {"averaged", "sampled"})};
}

CoarseNavierStokes2DOptions options_from(const json& s) {
  CoarseNavierStokes2DOptions o;
  o.cfl = s.at("cfl").get<double>();
  o.viscous_number = s.at("viscous_number").get<double>();
  return o;
}

// Far more steps than any cell here needs: a spec asking for more is refused at validation.
constexpr double kMaxSteps = 1e7;

class CoarseContinuum2D : public ExperimentKind {
 public:
  std::string name() const override { return "coarse_continuum_2d"; }
  std::string description() const override {
    return "coarse continuum Navier-Stokes baseline on the 2D reduced model's mesh (periodic: collocated, FFT "
           "projection; the cavity: staggered MAC, sparse projection; AB2), vs the exact field (the cavity: the same "
           "solver on a finer mesh), its average and the averaged direct SPH, with cost and speed-up";
  }

  std::vector<KindSection> sections() const override {
    return {{"scene",
             "the scene (required; doubly periodic with a cellular mode or a Taylor-Green vortex, or the lid-driven "
             "cavity)",
             "scene",
             {}},
            {"kernel",
             "the averaging kernel (initial average, mesh, direct SPH average); its eta the scene's",
             "kernel",
             {}},
            {"solver", "the continuum solver", "", solver_schema()},
            {"reference", "the direct SPH reference", "", reference_schema()},
            {"transient", "snapshots of both solvers", "", transient_schema()},
            {"timing", "how the baseline run is repeated for its time (minimum, median, spread)", "",
             reduced_timing_schema()}};
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    check_keys(cell, path, {"scene", "kernel", "solver", "reference", "transient", "timing"});
    json out;
    auto scene = build_scene(cell, path, reg, &out["scene"]);
    if (!scene->cellular_mode && !scene->taylor_green && !scene->cavity)
      throw ConfigError(path + "/scene", "scene '" + scene->name +
                                             "' has no exact single-mode solution (cellular mode or Taylor-Green "
                                             "vortex) and is not the cavity; use the cellular, taylor-green or "
                                             "lid-driven-cavity scene");
    auto kernel = build_kernel(cell, path, reg, scene->eta, &out["kernel"]);
    out["solver"] = resolve_section(cell, "solver", solver_schema(), path);
    out["reference"] = resolve_section(cell, "reference", reference_schema(), path);
    out["reference"]["solver"] =
        resolve_params(out["reference"]["solver"], sph_solver_schema(), path + "/reference/solver", {});
    check_time_loop(out["reference"]["solver"], path + "/reference/solver");
    if (out["reference"]["direct_sph"].get<bool>())
      check_direct_run(*scene, out["reference"]["solver"], path + "/reference/solver");
    out["transient"] = resolve_transient(cell, path);
    out["timing"] = resolve_section(cell, "timing", reduced_timing_schema(), path);
    TensorMesh2D mesh;
    try {
      mesh = continuum_mesh_for(*scene, *kernel, out["solver"]["spacing_over_eta"].get<double>());
    } catch (const ConfigError& e) {
      throw ConfigError(path + e.path(), e.message());
    }
    try {
      continuum_baseline_for(*scene, mesh, options_from(out["solver"]));
    } catch (const std::invalid_argument& e) {
      throw ConfigError(path + "/scene", e.what());
    }
    // The step count at the limits for the scene's peak speed (the modes here never exceed it).
    const double h = std::min(mesh.x.spacing, mesh.y.spacing), nu = scene->phase_viscosity[0] / scene->rho0;
    const double cfl = out["solver"]["cfl"].get<double>(), vn = out["solver"]["viscous_number"].get<double>();
    const double dt = std::min(vn * h * h / nu, scene->analytic_peak > 0 ? cfl * h / scene->analytic_peak : HUGE_VAL);
    const double steps = out["solver"]["target_time"].get<double>() / dt;
    if (!(steps <= kMaxSteps))
      throw ConfigError(path + "/solver/target_time",
                        "needs about " + std::to_string(steps) + " steps at the CFL and viscous limits (more than " +
                            std::to_string(kMaxSteps) + "); shorten it or coarsen the mesh");
    return out;
  }

  json upgraded_params(json stored) const override {
    return upgraded_reduced_params(ExperimentKind::upgraded_params(std::move(stored)));
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    const auto scene = reg.scenes.create(cfg.at("scene"), "/scene");
    const auto kernel = reg.kernels.create(cfg.at("kernel"), "/kernel");
    const json& solver_cfg = cfg.at("solver");
    const TensorMesh2D mesh = continuum_mesh_for(*scene, *kernel, solver_cfg.at("spacing_over_eta").get<double>());
    const double target = solver_cfg.at("target_time").get<double>(), scale = scene->analytic_peak;
    const double tau = scene->time_scale();
    const bool exact_mode = scene->taylor_green || scene->cellular_mode;  // else the cavity: no exact field
    const bool averaged_start = solver_cfg.at("initial") == "averaged";
    const AveragingKernel* force_average = solver_cfg.at("force") == "averaged" ? kernel.get() : nullptr;
    std::vector<double> times = transient_times(cfg.at("transient"), *scene);

    const std::optional<CellReference> direct =
        cell_reference(cfg, *scene, *kernel,
                       cfg.at("reference").at("observe_spacing_over_eta").get<double>() * scene->eta, times, progress);

    // The baseline run, repeated until its fastest time is stable; every run must give the same numbers.
    std::vector<std::pair<double, Field>> snapshots;
    Field final_field, start;
    long steps = 0;
    double last_dt = 0.0, reached = 0.0, removed = 0.0, divergence = 0.0;
    bool ok = true, repeats_identical = true;
    std::string method;
    int run_count = 0;
    const RepeatedReducedRuns timing = repeat_reduced_run(
        [&] {
          const auto t_setup = std::chrono::steady_clock::now();
          auto ns = continuum_baseline_for(*scene, mesh, options_from(solver_cfg), force_average);
          Eigen::VectorXd vx = Eigen::VectorXd::Zero(mesh.size()), vy = vx;
          if (scene->initial_velocity) {
            if (averaged_start) {
              const MesoFields f =
                  average_particles(scene->make_particles(), scene->box, *kernel, mesh, AveragingRequest{});
              vx = f.vx;
              vy = f.vy;
            } else {
              for (int n = 0; n < mesh.size(); ++n) {
                const Vec2 v = scene->initial_velocity(mesh.node(n).x(), mesh.node(n).y());
                vx[n] = v.x();
                vy[n] = v.y();
              }
            }
          }
          const double projected_off = ns->set_velocity(vx, vy);
          const double setup = seconds_since(t_setup);
          const auto t_loop = std::chrono::steady_clock::now();
          std::vector<std::pair<double, Field>> snaps;
          bool good = true;
          for (double t : times) {
            if (t > target) break;
            if (!(good = ns->advance_to(t))) break;
            snaps.push_back({t, Field{ns->vx(), ns->vy()}});
          }
          if (good) good = ns->advance_to(target);
          const double loop = seconds_since(t_loop);
          if (run_count++ > 0) {
            repeats_identical =
                repeats_identical && ns->vx() == final_field.x && ns->vy() == final_field.y && ns->steps() == steps;
          } else {
            final_field = Field{ns->vx(), ns->vy()};
            start = Field{vx, vy};
            snapshots = std::move(snaps);
            steps = ns->steps();
            last_dt = ns->time_step();
            reached = ns->time();
            removed = projected_off;
            divergence = ns->divergence().cwiseAbs().maxCoeff();
            method = ns->method();
            ok = good;
          }
          if (progress && run_count == 1)
            progress("coarse continuum: t = " + std::to_string(ns->time()) + ", " + std::to_string(ns->steps()) +
                     " steps");
          return ReducedRunSeconds{setup, loop};
        },
        timing_policy_from(cfg.at("timing")));

    json errors = json::object();
    json fields = {{"x", mesh.x.nodes()}, {"y", mesh.y.nodes()}, {"baseline", field_json(final_field)}};
    // The exact field on the mode (periodic scenes): e the kernel's symbol at the mode, unit its shape.
    const double k = exact_mode ? mode_wavenumber(*scene) : 0.0,
                 e = exact_mode ? kernel->symbol(Vec2(k, k) / (2.0 * M_PI)) : 0.0;
    const Field unit = exact_mode ? mode_shape(*scene, mesh) : Field{};
    const auto averaged_exact = [&](double t) { return scaled(unit, e * mode_amplitude(*scene, t)); };
    if (exact_mode) {
      const double a_final = mode_amplitude(*scene, reached);
      // The amplitude on the mode against the exact one (the ratio the discrete Laplacian sets: 2k²/|λ_h| at steady
      // state, e^{(2k² − |λ_h|) ν t} in a Taylor–Green decay) and against the averaged exact one.
      errors = {{"vs_analytic", norms(final_field, scaled(unit, a_final), scale)},
                {"vs_averaged_analytic", norms(final_field, averaged_exact(reached), scale)},
                {"amplitude",
                 {{"ratio", fitted(final_field, unit) / a_final},
                  {"ratio_to_averaged_analytic", fitted(final_field, unit) / (e * a_final)},
                  {"e", e}}}};
      fields["averaged_analytic"] = field_json(averaged_exact(reached));
    }
    // Without an exact field (the cavity, started at rest): the baseline seen through the averaging and the same
    // solver on a finer mesh in the exact field's place (coarse_continuum_scoring.hpp).
    BaselineViews views, fine;
    const bool replayed = !exact_mode && ok && start.x.isZero(0.0) && start.y.isZero(0.0) &&
                          walled_views(*scene, *kernel, mesh, options_from(solver_cfg), times, target, scale, views,
                                       fine, fields, errors);
    json cost = {{"steps", steps},
                 {"dt", last_dt},
                 {"model_time", reached},
                 {"coarse_nodes", mesh.size()},
                 {"initial_projection_removed", removed},
                 {"final_max_divergence", divergence}};
    json row;
    row["status"] = ok ? "ok" : "numerical_issue";
    if (!ok) row["message"] = "the continuum solve left the finite numbers (a step exceeded its stability limit?)";
    row["baseline"] = {{"method", method},
                       {"initial", solver_cfg.at("initial")},
                       {"force", solver_cfg.at("force")},
                       {"status", ok ? "target_time" : "numerical_issue"}};
    if (direct) {
      const auto average_of = [&](const ParticleSystem& ps) {
        const MesoFields f = average_particles(ps, scene->box, *kernel, mesh, AveragingRequest{});
        return Field{f.vx, f.vy};
      };
      const Field direct_field = average_of(direct->particles);
      const double direct_time = direct->record.at("time").get<double>();
      const std::vector<int> interior = interior_nodes(*scene, mesh);
      errors["vs_averaged_direct_sph"] = norms(final_field, direct_field, scale, interior);
      if (exact_mode)
        errors["direct_sph_vs_averaged_analytic"] = norms(direct_field, averaged_exact(direct_time), scale);
      if (replayed) {
        errors["averaged_baseline_vs_averaged_direct_sph"] = norms(views.at_target, direct_field, scale, interior);
        errors["direct_sph_vs_averaged_fine_continuum"] = norms(direct_field, fine.at_target, scale, interior);
      }
      fields["direct_average"] = field_json(direct_field);
      direct->record_into(row);
      json transient = json::array();
      for (std::size_t s = 0; s < times.size(); ++s) {
        const double t = times[s];
        json snap = {{"t_over_tau", t / tau}, {"time", t}};
        if (s < snapshots.size() && s < direct->snapshots.size()) {
          const Field& b = snapshots[s].second;
          const Field dsnap = average_of(direct->snapshots[s].particles);
          snap["baseline_vs_averaged_direct_sph"] = norms(b, dsnap, scale, interior);
          // Against the averaged direct field's own peak at this time (as reduced_model_2d reports it).
          snap["baseline_vs_averaged_direct_sph_at_its_peak"] =
              norms(b, dsnap, speed(dsnap).maxCoeff());
          if (exact_mode) {
            const Field avg_exact = averaged_exact(t);
            snap["baseline_vs_averaged_analytic"] = norms(b, avg_exact, scale);
            snap["direct_sph_vs_averaged_analytic"] = norms(dsnap, avg_exact, scale);
            snap["amplitude"] = {{"baseline", fitted(b, unit)},
                                 {"direct_sph_average", fitted(dsnap, unit)},
                                 {"averaged_analytic", fitted(avg_exact, unit)}};
          }
          if (replayed && s < views.at_times.size()) {
            snap["averaged_baseline_vs_averaged_direct_sph"] = norms(views.at_times[s], dsnap, scale, interior);
            snap["direct_sph_vs_averaged_fine_continuum"] = norms(dsnap, fine.at_times[s], scale, interior);
          }
        } else {
          snap["status"] = "not reached (a run ended before this time, or it is after the target time)";
        }
        transient.push_back(snap);
      }
      if (!transient.empty()) row["transient"] = transient;
      // The worst over the saved times (the measure of a transient the targets use) per region, without an exact field.
      if (!exact_mode && !transient.empty()) errors["worst_over_saved_times"] = worst_over_saved_times(transient);
    }
    finish_reduced_row(row, std::move(errors), std::move(cost), timing, repeats_identical, DeconvolutionIssues{},
                       direct ? direct->timed_run() : nullptr);
    row["fields"] = fields;
    return row;
  }

  // The direct reference dominates (particles n² times steps ~ n²); without it, the mesh.
  double expected_cost(const json& cfg) const override {
    const double n = cfg.at("scene").value("n", 48);
    return cfg.at("reference").at("direct_sph").get<bool>() ? n * n * n * n : n * n;
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_coarse_continuum_2d_experiment() { return std::make_unique<CoarseContinuum2D>(); }

}  // namespace closurelab
