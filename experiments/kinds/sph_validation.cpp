// Experiment kind "direct_sph_validation": the direct SPH reference of a scene, run to steady state
// (or a target time), averaged onto a column mesh, and compared with the analytic solution (5.15)/(D.3)
// and its Gaussian average; errors in the interior and in the wall band (nodes whose window reaches
// into a wall) separately, the effective wall position, the convective stress (App. B), and the cost.
// Scenes with phase interfaces (layered-two-phase, §7) add errors near/away from the interfaces and the
// final interface check (particles outside their phase region, row displacements, densities). Cellular
// scenes (not x-invariant) are compared in 2D instead (experiments/kinds/cellular_validation.cpp), porous-medium
// scenes by their permeability (experiments/kinds/permeability_validation.cpp), the Taylor-Green vortex by the decay
// of its largest speed (experiments/kinds/taylor_green_validation.cpp), the lid-driven cavity by its centre lines
// against Ghia's (experiments/kinds/cavity_validation.cpp).
#include "experiments/kinds/sph_validation.hpp"

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/scenes/analytic.hpp"
#include "core/averaging/averaging.hpp"
#include "core/base/metrics.hpp"
#include "core/sph/sph_engine.hpp"
#include "core/sph/sph_kernel.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/cell_config.hpp"
#include "experiments/kinds/cellular_validation.hpp"
#include "experiments/kinds/direct_reference.hpp"
#include "experiments/kinds/permeability_validation.hpp"
#include "experiments/kinds/cavity_validation.hpp"
#include "experiments/kinds/taylor_green_validation.hpp"
#include "core/scenes/ghia_cavity.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

namespace {

ParamSchema averaging_schema() {
  return {number_param("mesh_spacing_over_eta", 0.25, "row spacing of the averaging mesh / eta'", 0.01, 10.0)};
}

// Least-squares parabola through (y, v); returns its roots (the effective walls) and its peak.
struct ParabolaFit {
  double y1 = 0, y2 = 0, peak = 0;
};
ParabolaFit fit_parabola(const std::vector<double>& y, const std::vector<double>& v) {
  Eigen::MatrixXd a(y.size(), 3);
  Eigen::VectorXd b(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) {
    a(k, 0) = 1.0;
    a(k, 1) = y[k];
    a(k, 2) = y[k] * y[k];
    b[k] = v[k];
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(b);
  const double disc = std::sqrt(std::max(0.0, c[1] * c[1] - 4.0 * c[2] * c[0]));
  ParabolaFit f;
  f.y1 = (-c[1] + disc) / (2.0 * c[2]);
  f.y2 = (-c[1] - disc) / (2.0 * c[2]);
  if (f.y1 > f.y2) std::swap(f.y1, f.y2);
  const double ym = -c[1] / (2.0 * c[2]);
  f.peak = c[0] + c[1] * ym + c[2] * ym * ym;
  return f;
}

double distance_to_interface(const Scene& scene, double y) {
  double d = std::numeric_limits<double>::infinity();
  for (double yi : scene.interfaces) d = std::min(d, std::abs(y - yi));
  return d;
}

// The final state of a multi-phase scene against its initial phase layout: how far any fluid particle has
// strayed from the region of its phase (0 if every particle's phase still matches phase_at of its height),
// the largest y-displacement from its lattice row, and the density deviation (m n − ρ0)/ρ0 of the fluid
// particles within one SPH support of an interface and of the rest. All lengths in lattice spacings ε'.
json interface_check(const Scene& scene, const ParticleSystem& final_state, double support) {
  const ParticleSystem initial = scene.make_particles();  // the engine keeps the particle order
  ParticleSystem probe = final_state;
  SphEngine engine(scene, probe);
  engine.compute_accelerations();
  const std::vector<double>& n = engine.number_density();
  double outside = 0.0, shift = 0.0, near_shift = 0.0;
  double near_min = std::numeric_limits<double>::infinity(), near_max = -near_min, away_min = near_min,
         away_max = -near_min;
  int strayed = 0;
  for (std::size_t a = 0; a < final_state.size(); ++a) {
    if (final_state.fixed[a]) continue;
    const double y = final_state.y[a];
    const double dy = std::abs(y - initial.y[a]) / scene.dx;
    shift = std::max(shift, dy);
    if (scene.phase(y) != final_state.phase[a]) {
      ++strayed;
      outside = std::max(outside, distance_to_interface(scene, y) / scene.dx);
    }
    const double dev = (final_state.mass[a] * n[a] - scene.rho0) / scene.rho0;
    if (distance_to_interface(scene, initial.y[a]) < support) {
      near_shift = std::max(near_shift, dy);
      near_min = std::min(near_min, dev);
      near_max = std::max(near_max, dev);
    } else {
      away_min = std::min(away_min, dev);
      away_max = std::max(away_max, dev);
    }
  }
  json out = {{"count", scene.interfaces.size()},
              {"particles_outside_phase_region", strayed},
              {"max_distance_outside_phase_region_dx", outside},
              {"max_y_displacement_dx", shift},
              {"max_y_displacement_near_interfaces_dx", near_shift},
              {"density_deviation_near_interfaces", {{"min", near_min}, {"max", near_max}}},
              {"density_deviation_away_from_interfaces", {{"min", away_min}, {"max", away_max}}}};
  if (scene.van_der_waals) {
    const double n0 = scene.lattice_number_density();
    const VanDerWaalsEos& e = *scene.van_der_waals;
    out["van_der_waals"] = {{"kT", e.kt},
                            {"c1", e.c1},
                            {"c2", e.c2},
                            {"k_star", e.k_star},
                            {"n0", n0},
                            {"rest_pressure", e.pressure(n0, 1.0)},
                            {"sound_speed_at_n0", std::sqrt(e.dpressure_dn(n0, 1.0) / scene.particle_mass())},
                            {"interface_pressure_jump", e.interface_pressure_jump(n0)},
                            {"interface_pressure_jump_over_rho_c2",
                             e.interface_pressure_jump(n0) / (scene.rho0 * scene.sound_speed * scene.sound_speed)}};
  }
  return out;
}

class SphValidation : public ExperimentKind {
 public:
  std::string name() const override { return "direct_sph_validation"; }
  std::string description() const override {
    return "direct SPH of a scene to steady state, averaged, compared with the analytic solution and its average";
  }

  std::vector<KindSection> sections() const override {
    return {{"scene", "the scene (required)", "scene", {}},
            {"kernel", "the averaging kernel; its eta must equal the scene's", "kernel", {}},
            {"solver", "the direct SPH solver", "", sph_solver_schema()},
            {"averaging", "the averaging mesh", "", averaging_schema()}};
  }

  json upgraded_params(json stored) const override {
    stored = ExperimentKind::upgraded_params(std::move(stored));
    if (stored.is_object() && stored.contains("solver")) stored["solver"] = upgraded_sph_solver_params(stored["solver"]);
    return stored;
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    check_keys(cell, path, {"scene", "kernel", "solver", "averaging"});
    json out;
    auto scene = build_scene(cell, path, reg, &out["scene"]);
    if (!scene->analytic_vx && !scene->cellular_mode && !scene->permeability && !scene->taylor_green && !scene->cavity)
      throw ConfigError(path + "/scene", "scene '" + scene->name + "' has no analytic solution or reference");
    if (scene->cavity && !ghia_centrelines(scene->cavity->reynolds))
      throw ConfigError(path + "/scene/re", "the cavity's reference (Ghia, Ghia & Shin 1982) is tabulated at Re = 100, "
                                            "400 and 1000 only");
    build_kernel(cell, path, reg, scene->eta, &out["kernel"]);
    out["solver"] = resolve_section(cell, "solver", sph_solver_schema(), path);
    if (scene->taylor_green && out["solver"].at("mode") != "target_time")
      throw ConfigError(path + "/solver/mode", "the Taylor-Green vortex decays to rest: run it to a target_time");
    if (scene->cavity && out["solver"].at("mode") != "target_time")
      throw ConfigError(path + "/solver/mode", "the cavity is compared at the end of a target_time run (PySPH's "
                                               "t = 10)");
    check_time_loop(out["solver"], path + "/solver");
    check_direct_run(*scene, out["solver"], path + "/solver");
    out["averaging"] = resolve_section(cell, "averaging", averaging_schema(), path);
    return out;
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    using clock = std::chrono::steady_clock;
    const auto scene = reg.scenes.create(cfg.at("scene"), "/scene");
    const auto kernel = reg.kernels.create(cfg.at("kernel"), "/kernel");
    const double spacing = cfg.at("averaging").at("mesh_spacing_over_eta").get<double>() * scene->eta;
    if (scene->permeability) {  // porous media: the permeability against the scene's reference
      SphRunOptions opt = sph_run_options_from(cfg.at("solver"));
      opt.progress = progress;
      return run_permeability_validation(*scene, opt);
    }
    if (scene->taylor_green)  // the decay of the largest speed against the exact one, the particles stored at 20 times
      return run_taylor_green_validation(cfg, *scene, *kernel, spacing, progress);
    if (scene->cavity)  // the centre lines against Ghia's, the particles stored at 20 times
      return run_cavity_validation(cfg, *scene, *kernel, spacing, progress);
    if (scene->cellular_mode) {
      SphRunOptions opt = sph_run_options_from(cfg.at("solver"));
      opt.progress = progress;
      return run_cellular_validation(*scene, *kernel, opt, spacing);
    }
    const TensorMesh2D mesh = column_mesh(scene->box, spacing);
    const ReferenceRequest request{cfg.at("scene"), cfg.at("kernel"), cfg.at("solver"), mesh.y.spacing, {}};
    const StoredReference direct = stored_direct_reference(request, *scene, *kernel, progress);
    const ParticleSystem& ps = direct.particles;
    const SphRunResult sph = SphRunResult::from_json(direct.run);
    json row;
    row["status"] = row_status(sph.status);
    row["direct_sph"] = direct.run;
    if (!sph.message.empty()) row["message"] = sph.message;
    row["scene_derived"] = {{"dx", scene->dx},           {"eta", scene->eta},
                            {"l1", scene->wall_lo},      {"l2", scene->wall_hi},
                            {"h", scene->h},             {"sound_speed", scene->sound_speed},
                            {"analytic_peak", scene->analytic_peak}, {"particle_mass", scene->particle_mass()}};
    if (!scene->interfaces.empty()) row["scene_derived"]["interfaces"] = scene->interfaces;
    if (sph.status == Status::numerical_issue) return row;

    const double l1 = scene->wall_lo, l2 = scene->wall_hi, peak = scene->analytic_peak;
    const bool walls = scene->has_walls;
    const double support = scene->smoothing_kernel().support();
    if (!scene->interfaces.empty()) row["interfaces"] = interface_check(*scene, ps, support);

    // Particles against (5.15)/(D.3).
    std::vector<double> py, pv;
    for (std::size_t a = 0; a < ps.size(); ++a)
      if (!ps.fixed[a]) py.push_back(ps.y[a]), pv.push_back(ps.vx[a]);
    Eigen::VectorXd u(py.size()), ref(py.size());
    std::vector<bool> all(py.size(), true), interior(py.size()), band(py.size());
    for (std::size_t k = 0; k < py.size(); ++k) {
      u[k] = pv[k];
      ref[k] = scene->analytic_vx(py[k]);
      interior[k] = scene->in_interior(py[k]);
      band[k] = !interior[k];
    }
    json errors;
    errors["particles_vs_analytic"] = {{"all", error_norms(u, ref, all, peak).to_json()},
                                       {"interior", error_norms(u, ref, interior, peak).to_json()},
                                       {"wall_band", error_norms(u, ref, band, peak).to_json()}};
    errors["peak_relative_difference"] = peak_relative_difference(u, ref);
    if (!scene->interfaces.empty()) {
      // Particles within one SPH support of a phase interface, and the rest.
      std::vector<bool> near(py.size()), away(py.size());
      for (std::size_t k = 0; k < py.size(); ++k) {
        near[k] = distance_to_interface(*scene, py[k]) < support;
        away[k] = !near[k];
      }
      errors["particles_vs_analytic"]["near_interfaces"] = error_norms(u, ref, near, peak).to_json();
      errors["particles_vs_analytic"]["away_from_interfaces"] = error_norms(u, ref, away, peak).to_json();
    }

    // Averages on the column mesh.
    const auto t_avg = clock::now();
    AveragingRequest req;
    req.convective = true;
    req.components = {"xx", "xy"};
    const MesoFields f = average_particles(ps, scene->box, *kernel, mesh, req);
    const int nn = mesh.size();
    Eigen::VectorXd avg_ref(nn), point_ref(nn), tc_ref(nn);
    std::vector<bool> node_interior(nn), node_band(nn), node_channel(nn);
    const auto phi = [&](double t) { return kernel->factor(t); };
    json profile = {{"y", json::array()}, {"sph_average", json::array()}, {"analytic_average", json::array()},
                    {"analytic", json::array()}, {"convective_xx", json::array()}};
    for (int n = 0; n < nn; ++n) {
      const double y = mesh.node(n).y();
      const double r = kernel->support_radius();
      avg_ref[n] =
          average_by_quadrature(scene->analytic_vx, phi, r, y, walls ? l1 : y - r, walls ? l2 : y + r, scene->interfaces);
      point_ref[n] = scene->analytic_vx(y);
      node_channel[n] = scene->in_fluid(y);
      node_interior[n] = scene->in_interior(y);
      node_band[n] = node_channel[n] && !node_interior[n];
      profile["y"].push_back(y);
      profile["sph_average"].push_back(f.vx[n]);
      profile["analytic_average"].push_back(avg_ref[n]);
      profile["analytic"].push_back(point_ref[n]);
      profile["convective_xx"].push_back(f.convective.at("xx")[n]);
    }
    errors["averaged_vs_averaged_analytic"] = {
        {"interior", error_norms(f.vx, avg_ref, node_interior, peak).to_json()},
        {"wall_band", error_norms(f.vx, avg_ref, node_band, peak).to_json()}};
    errors["averaged_vs_analytic"] = {{"interior", error_norms(f.vx, point_ref, node_interior, peak).to_json()},
                                      {"wall_band", error_norms(f.vx, point_ref, node_band, peak).to_json()}};
    double tc_max = 0.0;
    for (int n = 0; n < nn; ++n)
      if (node_interior[n]) tc_max = std::max(tc_max, std::abs(f.convective.at("xx")[n]));
    errors["convective_xx_interior_max"] = tc_max;
    if (scene->uniform_force_x) {
      // Effective walls: the roots of the parabola fitted to the particle velocities; and App. B.
      const ParabolaFit fit = fit_parabola(py, pv);
      const double w = l2 - l1;
      errors["wall_offset"] = {{"fitted_lower_wall", fit.y1},
                               {"fitted_upper_wall", fit.y2},
                               {"shift_in_spacings", 0.5 * ((l1 - fit.y1) + (fit.y2 - l2)) / scene->dx},
                               {"centre_overprediction", (fit.peak - peak) / peak},
                               {"expected_2dx_over_w", 2.0 * scene->dx / w}};
      double tcb = 0.0, tc_err = 0.0;
      const double rho = scene->rho0, g = *scene->uniform_force_x, mu = scene->phase_viscosity[0];
      for (int n = 0; n < nn; ++n) {
        if (!node_interior[n]) continue;
        const double b = -rho * poiseuille_convective_stress_b(mesh.node(n).y(), l1, l2, rho, g, mu, kernel->eta());
        tcb = std::max(tcb, std::abs(b));
        tc_err = std::max(tc_err, std::abs(f.convective.at("xx")[n] - b));
      }
      errors["convective_xx_appendix_b_interior_max"] = tcb;
      errors["convective_xx_vs_appendix_b_max_abs"] = tc_err;
    }
    row["errors"] = errors;
    row["profile"] = profile;
    const double avg_seconds = std::chrono::duration<double>(clock::now() - t_avg).count();
    row["cost"] = sph.cost_json(avg_seconds);
    row["cost"]["peak_memory_mib"] = peak_memory_mib();
    return row;
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_sph_validation_experiment() { return std::make_unique<SphValidation>(); }

}  // namespace closurelab
