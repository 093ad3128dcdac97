// Experiment kind "coarse_continuum_2d": the coarse continuum Navier–Stokes baseline
// (core/continuum/coarse_navier_stokes_2d.hpp) on the 2D reduced model's own mesh (coarse_mesh_2d at the same
// spacing_over_eta), scored as reduced_model_2d scores the reduced model: against the exact field, its average and
// the averaged direct SPH of the same box (the same reference store entry when the reference sections match), at
// the final time and at the transient's snapshots, with the same cost columns (setup and loop timed apart, the
// speed-up over the direct run). Scenes: doubly periodic, one phase, with an exact single-mode solution (the
// cellular scene, forced or a Taylor–Green start; the taylor-green scene).
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
#include "core/continuum/coarse_navier_stokes_2d.hpp"
#include "core/reduced/meso_solver_2d.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/reduced_sections.hpp"
#include "experiments/runner/cell_config.hpp"

namespace closurelab {

namespace {

struct Field {
  Eigen::VectorXd x, y;
};

// The scene's mode at unit amplitude at the nodes: the Taylor–Green vortex (−cos kx sin ky, sin kx cos ky) or the
// cellular mode (sin kx cos ky, −cos kx sin ky); the exact velocity at time t is amplitude(t) times it.
Field mode_shape(const Scene& s, const TensorMesh2D& mesh) {
  Field f{Eigen::VectorXd(mesh.size()), Eigen::VectorXd(mesh.size())};
  for (int n = 0; n < mesh.size(); ++n) {
    const Vec2 q = mesh.node(n);
    if (s.taylor_green) {
      const double k = s.taylor_green->wavenumber;
      f.x[n] = -std::cos(k * q.x()) * std::sin(k * q.y());
      f.y[n] = std::sin(k * q.x()) * std::cos(k * q.y());
    } else {
      const double k = s.cellular_mode->wavenumber;
      f.x[n] = std::sin(k * q.x()) * std::cos(k * q.y());
      f.y[n] = -std::cos(k * q.x()) * std::sin(k * q.y());
    }
  }
  return f;
}

double amplitude(const Scene& s, double t) {
  return s.taylor_green ? s.taylor_green->factor(t) : s.cellular_mode->amplitude(t);
}

Field scaled(const Field& f, double a) { return Field{a * f.x, a * f.y}; }

double wavenumber(const Scene& s) { return s.taylor_green ? s.taylor_green->wavenumber : s.cellular_mode->wavenumber; }

json norms(const Field& u, const Field& ref, double scale) {
  const json n = vector_error_norms(u.x, u.y, ref.x, ref.y, scale).to_json();
  return {{"all_nodes", n},
          {"fluid_nodes", n},
          {"peak_relative_difference",
           peak_relative_difference(vector_magnitudes(u.x, u.y), vector_magnitudes(ref.x, ref.y))}};
}

// The least-squares amplitude of `f` relative to `unit`: Σ f · unit / Σ |unit|².
double fitted(const Field& f, const Field& unit) {
  return (f.x.dot(unit.x) + f.y.dot(unit.y)) / (unit.x.squaredNorm() + unit.y.squaredNorm());
}

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
    return "coarse continuum Navier-Stokes baseline (collocated central differences, AB2, FFT projection) on the 2D "
           "reduced model's mesh, vs the exact field, its average and the averaged direct SPH, with cost and speed-up";
  }

  std::vector<KindSection> sections() const override {
    return {
        {"scene", "the scene (required; doubly periodic with a cellular mode or a Taylor-Green vortex)", "scene", {}},
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
    if (!scene->cellular_mode && !scene->taylor_green)
      throw ConfigError(path + "/scene", "scene '" + scene->name +
                                             "' has no exact single-mode solution (cellular mode or Taylor-Green "
                                             "vortex); use the cellular or taylor-green scene");
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
      mesh = coarse_mesh_2d(*scene, *kernel, out["solver"]["spacing_over_eta"].get<double>());
    } catch (const ConfigError& e) {
      throw ConfigError(path + e.path(), e.message());
    }
    try {
      coarse_navier_stokes_for(*scene, mesh, options_from(out["solver"]));
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
    const TensorMesh2D mesh = coarse_mesh_2d(*scene, *kernel, solver_cfg.at("spacing_over_eta").get<double>());
    const double target = solver_cfg.at("target_time").get<double>(), scale = scene->analytic_peak;
    const double tau = scene->time_scale(), k = wavenumber(*scene);
    const bool averaged_start = solver_cfg.at("initial") == "averaged";
    const AveragingKernel* force_average = solver_cfg.at("force") == "averaged" ? kernel.get() : nullptr;
    std::vector<double> times = transient_times(cfg.at("transient"), *scene);

    const std::optional<CellReference> direct =
        cell_reference(cfg, *scene, *kernel,
                       cfg.at("reference").at("observe_spacing_over_eta").get<double>() * scene->eta, times, progress);

    // The baseline run, repeated until its fastest time is stable; every run must give the same numbers.
    std::vector<std::pair<double, Field>> snapshots;
    Field final_field;
    long steps = 0;
    double last_dt = 0.0, reached = 0.0, removed = 0.0, divergence = 0.0;
    bool ok = true, repeats_identical = true;
    int run_count = 0;
    const RepeatedReducedRuns timing = repeat_reduced_run(
        [&] {
          const auto t_setup = std::chrono::steady_clock::now();
          auto ns = coarse_navier_stokes_for(*scene, mesh, options_from(solver_cfg), force_average);
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
            snapshots = std::move(snaps);
            steps = ns->steps();
            last_dt = ns->time_step();
            reached = ns->time();
            removed = projected_off;
            divergence = ns->divergence().cwiseAbs().maxCoeff();
            ok = good;
          }
          if (progress && run_count == 1)
            progress("coarse continuum: t = " + std::to_string(ns->time()) + ", " + std::to_string(ns->steps()) +
                     " steps");
          return ReducedRunSeconds{setup, loop};
        },
        timing_policy_from(cfg.at("timing")));

    const double e = kernel->symbol(Vec2(k, k) / (2.0 * M_PI));
    const Field unit = mode_shape(*scene, mesh);
    const double a_final = amplitude(*scene, reached);
    const Field exact = scaled(unit, a_final), averaged = scaled(unit, e * a_final);
    // The amplitude on the mode against the exact one (the ratio the discrete Laplacian sets: 2k²/|λ_h| at steady
    // state, e^{(2k² − |λ_h|) ν t} in a Taylor–Green decay) and against the averaged exact one.
    json errors = {{"vs_analytic", norms(final_field, exact, scale)},
                   {"vs_averaged_analytic", norms(final_field, averaged, scale)},
                   {"amplitude",
                    {{"ratio", fitted(final_field, unit) / a_final},
                     {"ratio_to_averaged_analytic", fitted(final_field, unit) / (e * a_final)},
                     {"e", e}}}};
    const auto field_json = [](const Field& f) { return json{{"vx", f.x}, {"vy", f.y}}; };
    json fields = {{"x", mesh.x.nodes()},
                   {"y", mesh.y.nodes()},
                   {"baseline", field_json(final_field)},
                   {"averaged_analytic", field_json(averaged)}};
    json cost = {{"steps", steps},
                 {"dt", last_dt},
                 {"model_time", reached},
                 {"coarse_nodes", mesh.size()},
                 {"initial_projection_removed", removed},
                 {"final_max_divergence", divergence}};
    json row;
    row["status"] = ok ? "ok" : "numerical_issue";
    if (!ok) row["message"] = "the continuum solve left the finite numbers (a step exceeded its stability limit?)";
    row["baseline"] = {{"method", "collocated central differences, AB2, exact FFT projection"},
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
      errors["vs_averaged_direct_sph"] = norms(final_field, direct_field, scale);
      errors["direct_sph_vs_averaged_analytic"] =
          norms(direct_field, scaled(unit, e * amplitude(*scene, direct_time)), scale);
      fields["direct_average"] = field_json(direct_field);
      direct->record_into(row);
      json transient = json::array();
      for (std::size_t s = 0; s < times.size(); ++s) {
        const double t = times[s];
        json snap = {{"t_over_tau", t / tau}, {"time", t}};
        if (s < snapshots.size() && s < direct->snapshots.size()) {
          const Field& b = snapshots[s].second;
          const Field dsnap = average_of(direct->snapshots[s].particles),
                      avg_exact = scaled(unit, e * amplitude(*scene, t));
          snap["baseline_vs_averaged_direct_sph"] = norms(b, dsnap, scale);
          // Against the averaged direct field's own peak at this time (as reduced_model_2d reports it).
          snap["baseline_vs_averaged_direct_sph_at_its_peak"] = norms(b, dsnap, vector_magnitudes(dsnap.x, dsnap.y).maxCoeff());
          snap["baseline_vs_averaged_analytic"] = norms(b, avg_exact, scale);
          snap["direct_sph_vs_averaged_analytic"] = norms(dsnap, avg_exact, scale);
          snap["amplitude"] = {{"baseline", fitted(b, unit)},
                               {"direct_sph_average", fitted(dsnap, unit)},
                               {"averaged_analytic", fitted(avg_exact, unit)}};
        } else {
          snap["status"] = "not reached (a run ended before this time, or it is after the target time)";
        }
        transient.push_back(snap);
      }
      if (!transient.empty()) row["transient"] = transient;
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
