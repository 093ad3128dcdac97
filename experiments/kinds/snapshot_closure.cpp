// Experiment kind "snapshot_closure": the closure evaluated on a particle snapshot read from a file. The
// scene supplies the physics (box, walls, phases and viscosities, equation of state, SPH smoothing) and the
// fine mesh (its lattice rows); the snapshot supplies the particles (positions anywhere in the box). Steps:
//   b = v̄_x at the coarse data nodes (2.9) → x = deconvolution of b (§4) → the reconstruction at the fluid
//   particles (walls keep their velocities) → T_int,xy (2.13) of the pair forces (5.1) under the
//   reconstruction, against T_int,xy under the snapshot's own velocities, at the coarse nodes.
// The coarse meshes are the reduced model's (core/reduced/reduced_grid.hpp): nodes on both walls and the
// interior nodes as deconvolution data (a walled scene), or cell-centred nodes (periodic).
#include "experiments/kinds/snapshot_closure.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/metrics.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/reconstruction.hpp"
#include "core/io/h5part.hpp"
#include "core/io/particle_snapshot.hpp"
#include "core/reduced/reduced_grid.hpp"
#include "core/sph/sph_engine.hpp"
#include "experiments/kinds/cell_config.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

// experiments/kinds/reduced_sections.hpp (not included: its closure_schema() would clash with this kind's own).
void check_operator_shape(const json& closure, long rows, long cols, const std::string& path);

namespace {

ParamSchema snapshot_schema() {
  return {string_param("file", "", "particle file: .h5part/.h5/.hdf5 (H5Part layout or PySPH output) or .csv (x,y,vx,vy,mass,phase); "
                                   "a relative path is taken from the working folder"),
          integer_param("step", -1,
                        "H5Part step: the number N of the group Step#N (-1: the last); with step_by index, its place "
                        "among the steps the file has (0-based)",
                        -1, {}),
          string_param("step_by", "number",
                       "how the H5Part step is picked: number (step = N of Step#N), index (step = its place, 0-based) "
                       "or time (the one step whose TimeValue equals time)",
                       {"number", "index", "time"}),
          number_param("time", 0.0, "with step_by time: the TimeValue of the step to read (to 1e-9 relative)")};
}

// The step to read as read_particle_snapshot takes it: an H5Part file's group number (found by number, place or
// time among the Step#N groups it has); a CSV file's one step.
int snapshot_step(const std::string& file, const json& snapshot) {
  const std::string by = snapshot.at("step_by").get<std::string>();
  const int step = snapshot.at("step").get<int>();
  const std::string ext = std::filesystem::path(file).extension().string();
  const bool hdf5 = ext == ".h5part" || ext == ".h5" || ext == ".hdf5";
  if (!hdf5 || by == "number") return step;
  const long long number = h5part_select_step(file, by == "index" ? H5PartStepBy::index : H5PartStepBy::time, step,
                                              snapshot.at("time").get<double>());
  if (number > std::numeric_limits<int>::max())
    throw ConfigError("", "'" + file + "': step number " + std::to_string(number) + " is beyond the reader's range");
  return static_cast<int>(number);
}

ParamSchema closure_schema() {
  return {object_param("deconvolver", json{{"name", "landweber"}, {"order", 0}}, "registered deconvolver and its parameters"),
          string_param("discretization", "coarse_coarse", "discretization of R_eta (par. 4.2)",
                       {"coarse_coarse", "coarse_fine"}),
          number_param("spacing_over_eta", 1.0, "coarse mesh spacing / eta' (the paper: 1)", 0.05, 4.0),
          number_param("noise_level", 0.0, "delta handed to the deconvolver's parameter rule", 0.0, {})};
}

TensorMesh2D as_line(const UniformMesh1D& axis) { return TensorMesh2D{axis, UniformMesh1D{0.0, 1.0, 1, false, 0.0}}; }

// The reduced model's meshes (core/reduced/reduced_grid.hpp): stress at the coarse nodes, the interior nodes as
// deconvolution data, the lattice rows as the fine mesh; errors at path.
ReducedGrid meshes(const Scene& scene, const AveragingKernel& kernel, double spacing_over_eta, const std::string& path) {
  try {
    return make_reduced_grid(scene, kernel, spacing_over_eta, false, false);
  } catch (const ConfigError& e) {
    throw ConfigError(path, e.message());
  }
}

// The snapshot's particles checked against the scene: inside the box, known phases, the scene's number of
// particles; held-fixed flags from the scene's walls when the file has none.
ParticleSystem particles_for(const Scene& scene, ParticleSnapshot snap, const std::string& file) {
  ParticleSystem& p = snap.particles;
  if (p.size() == 0) throw ConfigError("/snapshot/file", "'" + file + "' holds no particles");
  for (std::size_t a = 0; a < p.size(); ++a) {
    if (p.x[a] < 0 || p.x[a] >= scene.box.lx || p.y[a] < 0 || p.y[a] >= scene.box.ly)
      throw ConfigError("/snapshot/file", "'" + file + "': particle " + std::to_string(a) + " at (" +
                                              std::to_string(p.x[a]) + ", " + std::to_string(p.y[a]) +
                                              ") lies outside the scene's box [0, lx) x [0, ly)");
    if (p.phase[a] >= static_cast<int>(scene.phase_viscosity.size()))
      throw ConfigError("/snapshot/file", "'" + file + "': particle " + std::to_string(a) + " has phase " +
                                              std::to_string(p.phase[a]) + ", the scene has " +
                                              std::to_string(scene.phase_viscosity.size()));
    if (!snap.has_fixed) p.fixed[a] = scene.is_wall(p.y[a]) ? 1 : 0;
  }
  // The pair forces take the scene's particle mass, so the snapshot must hold the scene's number of particles
  // (the box full at its lattice density; particles are conserved): a file cut at a line boundary, which every
  // line-by-line check passes, holds fewer.
  const std::size_t expected = scene.make_particles().size();
  if (p.size() != expected)
    throw ConfigError("/snapshot/file", "'" + file + "' holds " + std::to_string(p.size()) + " particles, the scene '" +
                                            scene.name + "' has " + std::to_string(expected) +
                                            ": a file cut short, or a snapshot of another scene or resolution");
  return p;
}

Eigen::VectorXd interaction_xy(const Scene& scene, ParticleSystem ps, const AveragingKernel& kernel,
                               const TensorMesh2D& nodes, long& pairs_out) {
  SphEngine engine(scene, ps);
  const std::vector<PairForce> pairs = engine.pair_forces();
  pairs_out = static_cast<long>(pairs.size());
  AveragingRequest req;
  req.interaction = true;
  req.components = {"xy"};
  return average_particles(ps, scene.box, kernel, nodes, req, pairs).interaction.at("xy");
}


class SnapshotClosure : public ExperimentKind {
 public:
  std::string name() const override { return "snapshot_closure"; }
  std::string description() const override {
    return "a particle snapshot from a file (H5Part or CSV) averaged, deconvolved, and the closure's stress (2.13) "
           "against the snapshot's exact stress";
  }

  std::vector<KindSection> sections() const override {
    return {{"scene", "the physics and geometry of the snapshot (an x-invariant scene, required)", "scene", {}},
            {"kernel", "the averaging kernel; its eta must equal the scene's", "kernel", {}},
            {"snapshot", "the particle file", "", snapshot_schema()},
            {"closure", "the deconvolution closure and the coarse mesh", "", closure_schema()}};
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    check_keys(cell, path, {"scene", "kernel", "snapshot", "closure"});
    json out;
    auto scene = build_scene(cell, path, reg, &out["scene"]);
    if (!scene->x_invariant) throw ConfigError(path + "/scene", "needs an x-invariant scene (column mesh)");
    auto kernel = build_kernel(cell, path, reg, scene->eta, &out["kernel"]);
    out["snapshot"] = resolve_section(cell, "snapshot", snapshot_schema(), path);
    {  // one way of picking the step: `time` only with step_by time, and then no `step`
      const json given = cell.contains("snapshot") && cell["snapshot"].is_object() ? cell["snapshot"] : json::object();
      const std::string by = out["snapshot"]["step_by"].get<std::string>();
      if (given.contains("time") && by != "time")
        throw ConfigError(path + "/snapshot/time", "a time picks the step only with \"step_by\": \"time\"");
      if (by == "time" && given.contains("step"))
        throw ConfigError(path + "/snapshot/step", "ambiguous: with \"step_by\": \"time\" the step is picked by "
                                                   "its time; give step or time, not both");
      if (by == "time" && !given.contains("time"))
        throw ConfigError(path + "/snapshot/time", "missing: \"step_by\": \"time\" needs the time of the step");
    }
    const std::string file = out["snapshot"]["file"].get<std::string>();
    if (file.empty()) throw ConfigError(path + "/snapshot/file", "missing: name a .h5part or .csv particle file");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
      throw ConfigError(path + "/snapshot/file", "'" + file + "' is not a readable file");
    // The file read and checked against the scene as the run reads it (the step there, the particles in the box,
    // their phases and count), so that --dry-run and the matrix's validation refuse what the cell would fail on.
    try {
      particles_for(*scene, read_particle_snapshot(file, snapshot_step(file, out["snapshot"])), file);
    } catch (const ConfigError& e) {
      throw ConfigError(path + "/snapshot/file", e.message());
    }
    out["closure"] = resolve_section(cell, "closure", closure_schema(), path);
    out["closure"]["deconvolver"] = reg.deconvolvers.resolve(out["closure"]["deconvolver"], path + "/closure/deconvolver");
    const ReducedGrid m =
        meshes(*scene, *kernel, out["closure"]["spacing_over_eta"].get<double>(), path + "/closure/spacing_over_eta");
    const bool coarse = out["closure"]["discretization"] == "coarse_coarse";  // else coarse_fine (the schema's two)
    check_operator_shape(out["closure"], m.data.count, coarse ? m.data.count : m.fine.count, path);
    return out;
  }

  json run(const json& cfg, const Registry& reg, const ProgressFn& progress) const override {
    using clock = std::chrono::steady_clock;
    const auto scene = reg.scenes.create(cfg.at("scene"), "/scene");
    const auto kernel = reg.kernels.create(cfg.at("kernel"), "/kernel");
    auto deconv = reg.deconvolvers.create(cfg.at("closure").at("deconvolver"), "/closure/deconvolver");
    const json& c = cfg.at("closure");
    const std::string file = cfg.at("snapshot").at("file").get<std::string>();
    const auto t0 = clock::now();
    progress("reading '" + file + "'");
    ParticleSnapshot snap;
    try {
      snap = read_particle_snapshot(file, snapshot_step(file, cfg.at("snapshot")));
    } catch (const ConfigError& e) {
      throw ConfigError("/snapshot/file", e.message());
    }
    const double snapshot_time = snap.time;
    const ParticleSystem ps = particles_for(*scene, std::move(snap), file);
    const double read_seconds = std::chrono::duration<double>(clock::now() - t0).count();

    // Average, deconvolve, reconstruct.
    const ReducedGrid m = meshes(*scene, *kernel, c.at("spacing_over_eta").get<double>(), "/closure/spacing_over_eta");
    const Eigen::VectorXd b = average_particles(ps, scene->box, *kernel, column_of(*scene, m.data), AveragingRequest{}).vx;
    const Discretization disc = parse_discretization(c.at("discretization").get<std::string>(), "/closure/discretization");
    const ForwardOperator a = make_averaging_operator_1d(*kernel, m.data, m.fine, disc);
    deconv->setup(a);
    const DeconvolutionResult r = deconv->solve(b, c.at("noise_level").get<double>());
    Eigen::VectorXd values = r.x;
    UniformMesh1D solution = disc == Discretization::coarse_coarse ? m.data : m.fine;
    if (scene->has_walls && disc == Discretization::coarse_coarse) {  // zero on the wall surfaces (no slip)
      values = Eigen::VectorXd::Zero(m.coarse.count);
      values.segment(1, r.x.size()) = r.x;
      solution = m.coarse;
    }
    const Reconstruction rec(as_line(solution), 1, values);
    ParticleSystem closed = ps;
    double v_scale = 0.0, v_err = 0.0;
    for (std::size_t k = 0; k < ps.size(); ++k) {
      if (ps.fixed[k]) continue;
      closed.vx[k] = rec.sample(Vec2(ps.y[k], 0.0));
      closed.vy[k] = 0.0;  // the closure of an x-invariant flow reconstructs v_x only
      v_scale = std::max(v_scale, std::abs(ps.vx[k]));
      v_err = std::max(v_err, std::abs(closed.vx[k] - ps.vx[k]));
    }

    // (2.13) under both velocity fields, at the coarse nodes.
    progress("pair forces and interaction stress of " + std::to_string(ps.size()) + " particles");
    const auto t_stress = clock::now();
    long pairs = 0;
    const Eigen::VectorXd t_exact = interaction_xy(*scene, ps, *kernel, column_of(*scene, m.coarse), pairs);
    const Eigen::VectorXd t_closure = interaction_xy(*scene, closed, *kernel, column_of(*scene, m.coarse), pairs);
    const double stress_seconds = std::chrono::duration<double>(clock::now() - t_stress).count();

    const int nn = m.coarse.count;
    const double l1 = scene->wall_lo, l2 = scene->wall_hi;
    std::vector<bool> channel(nn), interior(nn), band(nn);
    double scale = 0.0;
    for (int n = 0; n < nn; ++n) {
      const double y = m.coarse.node(n);
      channel[n] = !scene->has_walls || (y > l1 - 1e-12 && y < l2 + 1e-12);
      interior[n] = scene->in_interior(y);
      band[n] = channel[n] && !interior[n];
      if (channel[n]) scale = std::max(scale, std::abs(t_exact[n]));
    }
    json row;
    const bool finite = b.allFinite() && values.allFinite() && t_exact.allFinite() && t_closure.allFinite();
    row["status"] = !finite ? "numerical_issue"
                    : r.status == DeconvolutionStatus::converged ? "ok"
                                                                 : to_string(r.status);
    if (!finite) row["message"] = "non-finite averages, reconstruction or stress";
    if (finite && !(scale > 0)) {
      row["status"] = "numerical_issue";
      row["message"] = "the snapshot's exact T_xy vanishes in the channel (a fluid at rest?)";
    }
    row["snapshot"] = {{"time", snapshot_time}, {"particles", ps.size()}, {"pairs", pairs}};
    row["deconvolution"] = r.to_json();
    if (!r.stats.note.empty()) row["note"] = r.stats.note;  // the rule chose at the edge of its scan
    row["errors"] = {{"stress_xy", {{"channel", node_error_summary(t_closure, t_exact, channel, scale)},
                                    {"interior", node_error_summary(t_closure, t_exact, interior, scale)},
                                    {"wall_band", node_error_summary(t_closure, t_exact, band, scale)},
                                    {"max_abs_exact", scale}}},
                     {"particle_velocity_max_rel", v_scale > 0 ? v_err / v_scale : 0.0}};
    // A norm that is not a finite number (the data reached the edge of the double range) is no result.
    for (const char* part : {"channel", "interior", "wall_band"})
      for (const char* norm : {"max_rel", "l2_rel"}) {
        const json& v = row["errors"]["stress_xy"][part][norm];
        if (row["status"] == "ok" && v.is_number() && !std::isfinite(v.get<double>())) {
          row["status"] = "numerical_issue";
          row["message"] = std::string("non-finite stress error norm (") + part + "." + norm +
                           "): the data exceed the range in which the norms can be computed";
        }
      }
    row["profile"] = {{"y", m.coarse.nodes()}, {"exact_xy", t_exact}, {"closure_xy", t_closure},
                      {"y_data", m.data.nodes()}, {"averaged_vx", b}};
    row["cost"] = {{"read_seconds", read_seconds},
                   {"deconvolution_seconds", r.cost.setup_seconds + r.cost.solve_seconds},
                   {"stress_seconds", stress_seconds},
                   {"peak_memory_mib", peak_memory_mib()}};
    return row;
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_snapshot_closure_experiment() { return std::make_unique<SnapshotClosure>(); }

}  // namespace closurelab
