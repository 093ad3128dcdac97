// Experiment kind "quadrature_convergence" (Appendix C): the interaction stress T_int,xy of one velocity
// field by the exact pair sum (2.13) and by the configured quadrature (the coarse one (5.27), whose R-grid
// spacing the matrix sweeps), on the column mesh of an x-invariant scene. The field is the zero-order closure
// of the steady state: the analytic profile (5.15)/(D.3) itself, or its Gaussian average (the closure applied
// to the averaged analytic solution), on the fluid particles, with the walls at rest (5.3). Errors relative to
// max |T_exact| over the channel, in the interior and the wall band (nodes within 3 η' of a wall) separately.
#include "experiments/kinds/quadrature_convergence.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "core/scenes/analytic.hpp"
#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/metrics.hpp"
#include "core/closure/stress_quadrature.hpp"
#include "experiments/kinds/cell_config.hpp"
#include "experiments/kinds/provenance.hpp"
#include "strategies/quadrature/coarse_quadrature.hpp"
#include "strategies/quadrature/exact_quadrature.hpp"

namespace closurelab {

namespace {

ParamSchema evaluation_schema() {
  return {string_param("velocity", "analytic",
                       "zero-order closure field on the fluid particles: the analytic steady profile, or its "
                       "Gaussian average (walls at rest either way)",
                       {"analytic", "averaged_analytic"}),
          number_param("mesh_spacing_over_eta", 0.25, "row spacing of the column mesh of nodes / eta'", 0.01, 10.0),
          integer_param("repeats", 3, "evaluations per quadrature (the minimum time is reported)", 1, 100)};
}

// Seconds of the fastest of `repeats` evaluations, the last result, and the cost (setup and calls).
struct TimedEvaluation {
  double best_seconds = 1e300;
  Eigen::VectorXd xy;
  QuadratureCost cost;
};
TimedEvaluation timed_evaluate(StressQuadrature& q, const VelocitySampler& v, int repeats) {
  TimedEvaluation out;
  out.cost = q.setup_cost();
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const QuadratureResult r = q.evaluate(v);
    out.best_seconds = std::min(out.best_seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    out.cost.add(r);
    if (r.status != Status::converged) throw NumericalError(r.message);
    out.xy = r.stress.at("xy");
  }
  return out;
}


class QuadratureConvergence : public ExperimentKind {
 public:
  std::string name() const override { return "quadrature_convergence"; }
  std::string description() const override {
    return "error and cost of a stress quadrature (coarse (5.27)) against the exact pair sum (2.13), App. C";
  }

  std::vector<KindSection> sections() const override {
    return {{"scene", "an x-invariant scene (required)", "scene", {}},
            {"kernel", "the averaging kernel; its eta must equal the scene's", "kernel", {}},
            {"quadrature", "the stress quadrature under test (required)", "quadrature", {}},
            {"evaluation", "the closure field and the column mesh", "", evaluation_schema()}};
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    check_keys(cell, path, {"scene", "kernel", "quadrature", "evaluation"});
    json out;
    auto scene = build_scene(cell, path, reg, &out["scene"]);
    if (!scene->analytic_vx) throw ConfigError(path + "/scene", "scene '" + scene->name + "' has no analytic solution");
    if (!scene->x_invariant) throw ConfigError(path + "/scene", "needs an x-invariant scene (column mesh)");
    auto kernel = build_kernel(cell, path, reg, scene->eta, &out["kernel"]);
    if (!cell.contains("quadrature")) throw ConfigError(path + "/quadrature", "missing; known: " + reg.quadratures.known_names());
    auto q = reg.quadratures.create(cell.at("quadrature"), path + "/quadrature", &out["quadrature"]);
    out["evaluation"] = resolve_section(cell, "evaluation", evaluation_schema(), path);
    if (q->name() == "coarse") {  // cheap (O(N_C J)): checks that the R-grid tiles the lattice before running
      const TensorMesh2D mesh = column_mesh(scene->box, out["evaluation"]["mesh_spacing_over_eta"].get<double>() * scene->eta);
      try {
        q->setup(*scene, *kernel, mesh, {"xy"});
      } catch (const ConfigError& e) {
        throw ConfigError(path + "/quadrature" + e.path(), e.message());
      }
    }
    return out;
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    const auto scene = reg.scenes.create(cfg.at("scene"), "/scene");
    const auto kernel = reg.kernels.create(cfg.at("kernel"), "/kernel");
    auto quadrature = reg.quadratures.create(cfg.at("quadrature"), "/quadrature");
    const json& ev = cfg.at("evaluation");
    const int repeats = ev.at("repeats").get<int>();
    const TensorMesh2D mesh = column_mesh(scene->box, ev.at("mesh_spacing_over_eta").get<double>() * scene->eta);
    const double l1 = scene->wall_lo, l2 = scene->wall_hi, eta = scene->eta;

    // The zero-order closure field v_x(y) (x-invariant), cached per row.
    const bool averaged = ev.at("velocity") == "averaged_analytic";
    std::map<double, double> cache;
    const auto vx = [&](double y) {
      auto it = cache.find(y);
      if (it != cache.end()) return it->second;
      const double v = averaged ? average_by_quadrature(scene->analytic_vx, [&](double t) { return kernel->factor(t); },
                                                        kernel->support_radius(), y, l1, l2)
                                : scene->analytic_vx(y);
      return cache[y] = v;
    };
    const VelocitySampler sampler = [&](const std::vector<Vec2>& pts) {
      Eigen::Matrix2Xd v = Eigen::Matrix2Xd::Zero(2, pts.size());
      for (std::size_t k = 0; k < pts.size(); ++k)
        if (!scene->is_wall(pts[k].y())) v(0, k) = vx(pts[k].y());
      return v;
    };

    progress("exact quadrature: setup");
    ExactQuadrature exact;
    exact.setup(*scene, *kernel, mesh, {"xy"});
    const TimedEvaluation exact_run = timed_evaluate(exact, sampler, repeats);
    const double t_exact = exact_run.best_seconds;
    const Eigen::VectorXd& te = exact_run.xy;
    progress("quadrature '" + quadrature->name() + "': setup and evaluation");
    quadrature->setup(*scene, *kernel, mesh, {"xy"});
    const TimedEvaluation quadrature_run = timed_evaluate(*quadrature, sampler, repeats);
    const double t_q = quadrature_run.best_seconds;
    const Eigen::VectorXd& tq = quadrature_run.xy;

    const int nn = mesh.size();
    std::vector<bool> channel(nn), interior(nn), band(nn), walls(nn);
    json profile = {{"y", json::array()}, {"exact", json::array()}, {"quadrature", json::array()}};
    double scale = 0.0;
    for (int n = 0; n < nn; ++n) {
      const double y = mesh.node(n).y();
      channel[n] = scene->in_fluid(y);
      interior[n] = scene->in_interior(y);
      band[n] = scene->in_wall_band(y);
      walls[n] = !channel[n];
      if (channel[n]) scale = std::max(scale, std::abs(te[n]));
      profile["y"].push_back(y);
      profile["exact"].push_back(te[n]);
      profile["quadrature"].push_back(tq[n]);
    }
    if (!(scale > 0)) throw NumericalError("exact T_xy vanishes in the channel");
    json row;
    row["status"] = "ok";
    row["errors"] = {{"channel", node_error_summary(tq, te, channel, scale)},
                     {"interior", node_error_summary(tq, te, interior, scale)},
                     {"wall_band", node_error_summary(tq, te, band, scale)},
                     {"inside_walls", node_error_summary(tq, te, walls, scale)},
                     {"max_abs_exact_xy", scale}};
    json derived = {{"particles", static_cast<double>(scene->nx) * scene->ny}, {"dx", scene->dx}, {"eta", eta}};
    if (const auto* c = dynamic_cast<const CoarseQuadrature*>(quadrature.get())) {
      const int sx = cfg.at("quadrature").at("stride_x").get<int>(), sy = cfg.at("quadrature").at("stride_y").get<int>();
      derived["coarse_spacing_over_eta"] = sy * scene->dx / eta;
      derived["coarsening_strip"] = c->coarsening();  // N/N_C of this strip
      // The paper's N/N_C on its square domain: s_x s_y; with the x-integrated column (s_x → the exact limit)
      // a square R-grid of the same y-spacing, s_y².
      derived["coarsening_paper_equivalent"] = sx > 0 ? sx * sy : sy * sy;
      derived["r_nodes"] = c->r_nodes();
      derived["offsets_J"] = c->offsets();
      derived["virtual_pairs"] = c->virtual_pairs();
    }
    row["derived"] = derived;
    row["cost"] = {{"exact", exact_run.cost.to_json()},
                   {"quadrature", quadrature_run.cost.to_json()},
                   {"exact_evaluate_seconds_min", t_exact},
                   {"quadrature_evaluate_seconds_min", t_q},
                   {"evaluate_speedup", t_q > 0 ? t_exact / t_q : 0.0},
                   {"pair_forces_ratio",
                    static_cast<double>(exact.pair_count()) / std::max<long>(1, quadrature_run.cost.pair_forces / repeats)},
                   {"peak_memory_mib", peak_memory_mib()}};
    row["profile"] = profile;
    return row;
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_quadrature_convergence_experiment() {
  return std::make_unique<QuadratureConvergence>();
}

}  // namespace closurelab
