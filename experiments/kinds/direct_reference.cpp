#include "experiments/kinds/direct_reference.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/sph/engine_version.hpp"
#include "experiments/kinds/reference_profiles.hpp"

namespace closurelab {

namespace {
// The node count in 64-bit arithmetic (TensorMesh2D::size() is an int).
long long node_count(const TensorMesh2D& m) { return static_cast<long long>(m.nx()) * m.ny(); }

constexpr double kMaxAxisNodes = 2147483647.0;  // INT_MAX: TensorMesh2D counts its nodes in an int

std::string short_number(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v;
  return os.str();
}
}  // namespace

DirectReference run_direct_reference(const Scene& scene, const AveragingKernel& kernel, SphRunOptions options,
                                     const TensorMesh2D& observed) {
  DirectReference ref{scene.make_particles(), {}};
  // Averaging onto a fine observation mesh can take longer than the steps between two tests (2D at
  // observe_spacing_over_eta = 0.01: 2.6e6 nodes, about 12 s each, 72 s with one progress line before): say so
  // up front for a large mesh, and report each average slower than kSlowObservation, at most once per progress interval.
  constexpr double kSlowObservation = 2.0;  // seconds
  constexpr int kLargeObservation = 100000;  // nodes
  const std::function<void(const std::string&)> progress = options.progress;
  if (progress && node_count(observed) > kLargeObservation)
    progress("the steady test averages " + std::to_string(ref.particles.size()) + " particles onto " +
             std::to_string(node_count(observed)) + " nodes (observe spacing " + short_number(observed.y.spacing) +
             ") every " + std::to_string(options.steady_window) + " steps");
  using clock = std::chrono::steady_clock;
  auto last_report = clock::now() - std::chrono::hours(1);
  int averages = 0;
  options.observable = [&, progress](const ParticleSystem& p) {
    const auto t0 = clock::now();
    Eigen::VectorXd v = average_particles(p, scene.box, kernel, observed, AveragingRequest{}).vx;
    const auto t1 = clock::now();
    ++averages;
    const double took = std::chrono::duration<double>(t1 - t0).count();
    if (progress && took >= kSlowObservation &&
        std::chrono::duration<double>(t1 - last_report).count() >= options.progress_seconds) {
      last_report = t1;
      progress("steady test: average " + std::to_string(averages) + " onto " + std::to_string(node_count(observed)) +
               " nodes took " + short_number(took) + " s (observe_spacing_over_eta sets this mesh; coarser is faster)");
    }
    return v;
  };
  ref.run = run_direct_sph(scene, ref.particles, options);
  return ref;
}

void check_observe_mesh(const Scene& scene, double spacing, const std::string& path) {
  // In double: at a tiny eta' the counts outgrow an int (n = 32, eta' = 1e-6 L: 1e10 nodes wrapped to 1410065408).
  const double along_x = scene.x_invariant ? 1.0 : std::max(1.0, std::round(scene.box.lx / spacing));
  const double along_y = std::max(1.0, std::round(scene.box.ly / spacing));
  const double nodes = along_x * along_y;
  if (!(along_x <= kMaxAxisNodes && along_y <= kMaxAxisNodes && nodes <= kMaxAxisNodes))
    throw ConfigError(path, "the steady test's observation mesh (spacing " + short_number(spacing) + ", " +
                                short_number(along_x) + " x " + short_number(along_y) + " nodes) has more nodes than "
                                "an int counts; raise observe_spacing_over_eta or the scene's eta'");
  // Each average holds the density, momenta and velocities (5 doubles a node); the steady test keeps the last two.
  check_allocation(nodes, 2 * 5 * sizeof(double), "the steady test's observation mesh of " + short_number(nodes) +
                                                      " nodes (spacing " + short_number(spacing) + ")", path);
}

TensorMesh2D observe_mesh(const Scene& scene, double spacing) {
  check_observe_mesh(scene, spacing, "/reference/observe_spacing_over_eta");
  if (scene.x_invariant) return column_mesh(scene.box, spacing);
  const auto axis = [spacing](double length, bool periodic) {
    return UniformMesh1D::cell_centred(0.0, length, std::max(1, static_cast<int>(std::lround(length / spacing))), periodic);
  };
  return {axis(scene.box.lx, scene.box.periodic_x), axis(scene.box.ly, scene.box.periodic_y)};
}

json reference_key(const ReferenceRequest& r) {
  json solver = r.solver;
  solver.erase("progress_seconds");
  // The standard formulation's key is the one it had before the formulation was a parameter (its stored runs stay
  // valid), and the transport velocity's background pressure does not enter it.
  if (solver.value("formulation", "standard") == "standard") {
    solver.erase("formulation");
    solver.erase("transport_background_pressure_factor");
  }
  // The channels and kolmogorov stored their averaging width as eta_over_ly before every scene named it eta_over_l:
  // their key keeps that name, so the references stored before stay valid.
  json scene = r.scene;
  const std::string scene_name = scene.value("name", "");
  if (scene.contains("eta_over_l") &&
      (scene_name == "poiseuille-uniform" || scene_name == "poiseuille-periodic" || scene_name == "kolmogorov")) {
    scene["eta_over_ly"] = scene["eta_over_l"];
    scene.erase("eta_over_l");
  }
  return {{"kind", "direct_sph"},
          {"engine_version", sph_engine_version},
          {"scene", scene},
          {"kernel", r.kernel},
          {"solver", solver},
          {"observe_spacing", r.observe_spacing},
          {"snapshot_times", r.snapshot_times}};
}

StoredReference stored_direct_reference(const ReferenceRequest& request, const Scene& scene,
                                        const AveragingKernel& kernel,
                                        const std::function<void(const std::string&)>& progress) {
  StoredReference ref = reference_store().get_or_compute(reference_key(request), [&] {
    StoredReference computed;
    SphRunOptions opt = sph_run_options_from(request.solver);
    opt.progress = progress;
    opt.snapshot_times = request.snapshot_times;
    opt.on_snapshot = [&computed](double t, const ParticleSystem& p) { computed.snapshots.push_back({t, p, true}); };
    DirectReference d = run_direct_reference(scene, kernel, opt, observe_mesh(scene, request.observe_spacing));
    computed.particles = std::move(d.particles);
    computed.run = d.run.to_json();
    return computed;
  });
  ref.run["reference_store"] = ref.store;
  return ref;
}

std::optional<CellReference> cell_reference(const json& cfg, const Scene& scene, const AveragingKernel& kernel,
                                            double observe_spacing, const std::vector<double>& snapshot_times,
                                            const std::function<void(const std::string&)>& progress) {
  const json& section = cfg.at("reference");
  const std::string file = section.value("file", "");
  if (!file.empty()) {
    if (progress) progress("reading the reference '" + file + "'");
    ReferenceFile f = read_reference_file(scene, file, section.at("step").get<int>(), "/reference/file");
    return CellReference{std::move(f.particles), {}, std::move(f.record), true};
  }
  if (!section.at("direct_sph").get<bool>()) return std::nullopt;
  const ReferenceRequest request{cfg.at("scene"), cfg.at("kernel"), section.at("solver"), observe_spacing,
                                 snapshot_times};
  StoredReference stored = stored_direct_reference(request, scene, kernel, progress);
  return CellReference{std::move(stored.particles), std::move(stored.snapshots), std::move(stored.run), false};
}

}  // namespace closurelab
