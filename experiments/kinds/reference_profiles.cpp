#include "experiments/kinds/reference_profiles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/io/pysph_output.hpp"
#include "experiments/kinds/permeability_validation.hpp"
#include "experiments/kinds/reduced_sections.hpp"
#include "experiments/kinds/reference_store.hpp"

namespace closurelab {

Eigen::VectorXd average_on_nodes(const ParticleSystem& particles, const Scene& scene, const AveragingKernel& kernel,
                                 const Eigen::VectorXd& nodes) {
  UniformMesh1D axis{nodes[0], nodes.size() > 1 ? nodes[1] - nodes[0] : 1.0, static_cast<int>(nodes.size()),
                     !scene.has_walls, scene.has_walls ? 0.0 : scene.box.ly};
  const TensorMesh2D mesh{UniformMesh1D{0.0, scene.box.lx, 1, true, scene.box.lx}, axis};
  return average_particles(particles, scene.box, kernel, mesh, AveragingRequest{}).vx;
}

ReferenceProfiles reference_profiles(const ParticleSystem& particles, const Scene& scene,
                                     const AveragingKernel& kernel, const Eigen::VectorXd& nodes) {
  std::map<long, std::pair<double, int>> rows;  // lattice row → (Σ v_x, count) over the fluid particles
  for (std::size_t a = 0; a < particles.size(); ++a) {
    if (particles.fixed[a]) continue;
    auto& r = rows[std::lround(particles.y[a] / scene.dx - 0.5)];
    r.first += particles.vx[a];
    ++r.second;
  }
  ReferenceProfiles out;
  out.row_y.resize(static_cast<Eigen::Index>(rows.size()));
  out.row_velocity.resize(static_cast<Eigen::Index>(rows.size()));
  Eigen::Index i = 0;
  for (const auto& [row, sum] : rows) {
    out.row_y[i] = (row + 0.5) * scene.dx;
    out.row_velocity[i++] = sum.first / sum.second;
  }
  out.averaged = average_on_nodes(particles, scene, kernel, nodes);
  out.particles = particles;
  return out;
}

ParamSchema reference_file_schema() {
  return {string_param("file", "",
                       "a particle snapshot as the reference instead of the direct SPH run: .h5part/.h5/.hdf5 (H5Part "
                       "layout or PySPH's own output) or .csv (x,y,vx,vy,mass,phase[,fixed]); averaged onto the "
                       "coarse nodes as the direct run's final state is; no transient, no speed-up"),
          integer_param("step", -1, "with file: the H5Part step N of Step#N (-1: the last; PySPH output and CSV: 0 or -1)",
                        -1, {})};
}

ParamSchema reference_with_file_schema() {
  ParamSchema s = reference_schema();
  for (auto& p : reference_file_schema()) s.push_back(std::move(p));
  return s;
}

json with_reference_file_defaults(json params) {
  if (params.is_object() && params.contains("reference") && params["reference"].is_object()) {
    json& ref = params["reference"];
    for (const ParamSpec& p : reference_file_schema())
      if (!ref.contains(p.name)) ref[p.name] = p.default_value;
  }
  return params;
}

namespace {

std::string layout_of(const std::string& file) {
  if (is_pysph_output(file)) return "pysph_output";
  const std::string ext = std::filesystem::path(file).extension().string();
  return ext == ".csv" ? "csv" : "h5part";
}

std::string hex16(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::string number(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

// A file that scores must be a state of this scene (a file of another radius, of the cylinder lattice for
// the cylinder channel, PySPH's fluid and solid arrays swapped, a state at rest or with a runaway particle all scored
// `ok` before): its held-fixed particles are the scene's solids (Scene::make_particles' flags), its fluid moves, no
// particle outruns the scene's sound speed, and its flow has the expected sign.
void check_state_against_scene(const Scene& scene, const ParticleSystem& p, bool has_fixed, const std::string& file,
                               const std::string& path) {
  const auto refuse = [&](const std::string& why) { throw ConfigError(path, "'" + file + "': " + why); };
  const ParticleSystem lattice = scene.make_particles();  // row j, column i at j * nx + i
  const auto site_of = [&](double x, double y) {
    const long i = std::clamp<long>(std::lround(x / scene.dx - 0.5), 0, scene.nx - 1);
    const long j = std::clamp<long>(std::lround(y / scene.dx - 0.5), 0, scene.ny - 1);
    return static_cast<std::size_t>(j * scene.nx + i);
  };
  const long scene_fixed = std::count(lattice.fixed.begin(), lattice.fixed.end(), 1);
  const long scene_fluid = static_cast<long>(lattice.size()) - scene_fixed;
  long file_fixed = 0, misplaced = 0, moving_solid = 0, resting_fluid = 0;
  std::size_t first_misplaced = 0, first_moving = 0;
  double fastest = 0.0;
  std::size_t fastest_at = 0;
  bool fluid_moves = false;
  for (std::size_t a = 0; a < p.size(); ++a) {
    const std::size_t site = site_of(p.x[a], p.y[a]);
    const double speed = std::hypot(p.vx[a], p.vy[a]);
    if (speed > fastest) fastest = speed, fastest_at = a;
    if (p.fixed[a]) {
      ++file_fixed;
      // A held particle never moves: it lies on a site the scene holds (a quarter spacing allows the file's rounding).
      const bool on_site = std::hypot(p.x[a] - lattice.x[site], p.y[a] - lattice.y[site]) <= 0.25 * scene.dx;
      if (has_fixed && (!lattice.fixed[site] || !on_site) && misplaced++ == 0) first_misplaced = a;
      if (!has_fixed && speed > 0 && moving_solid++ == 0) first_moving = a;
    } else {
      fluid_moves = fluid_moves || speed > 0;
      if (speed == 0) ++resting_fluid;
    }
  }
  if (has_fixed && (file_fixed != scene_fixed || misplaced > 0)) {
    std::string why = "its held-fixed (solid) particles are not the scene's: the file holds " +
                      std::to_string(file_fixed) + ", the scene '" + scene.name + "' " + std::to_string(scene_fixed);
    if (misplaced > 0)
      why += "; " + std::to_string(misplaced) + " of the file's lie where the scene has fluid (particle " +
             std::to_string(first_misplaced) + " at (" + number(p.x[first_misplaced]) + ", " +
             number(p.y[first_misplaced]) + "))";
    refuse(why + ": a snapshot of another geometry (a cylinder of another radius, walls the scene lacks) or with its "
                 "fluid and solid swapped");
  }
  // Without flags the scene decides which particles are held (read_reference_file); the file's own velocities must
  // agree: held particles at rest, fluid particles moving. 1 % of each set may disagree (a fluid particle that
  // drifted onto a site the scene holds; Morris's ghost-velocity walls store a velocity on the wall particles).
  if (!has_fixed && scene.wall_model == WallModel::zero_velocity && moving_solid > 0.01 * scene_fixed)
    refuse(std::to_string(moving_solid) + " of the " + std::to_string(scene_fixed) + " particles the scene '" +
           scene.name + "' holds at rest move in the file (particle " + std::to_string(first_moving) + " at (" +
           number(p.x[first_moving]) + ", " + number(p.y[first_moving]) + ")): a snapshot of another geometry");
  if (!fluid_moves)
    refuse("every fluid particle is at rest (a state at t = 0?): a reference at rest has no velocity to be relative to");
  if (!has_fixed && resting_fluid > 0.01 * scene_fluid)
    refuse(std::to_string(resting_fluid) + " of the scene's " + std::to_string(scene_fluid) + " fluid particles are "
           "exactly at rest in the file: solid where the scene '" + scene.name + "' has fluid (another geometry)");
  if (scene.sound_speed > 0 && fastest > scene.sound_speed)
    refuse("particle " + std::to_string(fastest_at) + " moves at " + number(fastest) + ", faster than the scene's sound "
           "speed " + number(scene.sound_speed) + ": not a state of this weakly compressible scene (Mach << 1)");
  // The flow's sign: a positive Darcy permeability; along a channel, the mean v_x of the analytic solution's sign.
  if (scene.permeability) {
    const double k = darcy_permeability(scene, p);
    if (!(k > 0))
      refuse("its Darcy permeability mu <u_x> / (rho g) is " + number(k) + ", not positive: a flow against the body "
             "force (or none)");
  } else if (scene.analytic_vx && scene.has_walls) {
    double expected = 0.0, got = 0.0;
    long n = 0;
    for (std::size_t a = 0; a < p.size(); ++a)
      if (!p.fixed[a]) expected += scene.analytic_vx(p.y[a]), got += p.vx[a], ++n;
    if (n > 0 && std::abs(expected) > 0.1 * scene.analytic_peak * n && !(got * expected > 0))
      refuse("its mean fluid v_x is " + number(got / n) + ", the scene's analytic mean " + number(expected / n) +
             ": a flow of the other sign");
  }
}

}  // namespace

ReferenceFile read_reference_file(const Scene& scene, const std::string& file, int step, const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw ConfigError(path, "'" + file + "' is not a readable file");
  ParticleSnapshot snap;
  try {
    snap = read_particle_snapshot(file, step);
  } catch (const ConfigError& e) {
    throw ConfigError(path, e.message());
  } catch (const std::exception& e) {
    throw ConfigError(path, "'" + file + "': " + e.what());
  }
  ParticleSystem& p = snap.particles;
  const std::size_t expected = scene.make_particles().size();
  if (p.size() != expected)
    throw ConfigError(path, "'" + file + "' holds " + std::to_string(p.size()) + " particles, the scene '" + scene.name +
                                "' has " + std::to_string(expected) + ": a snapshot of another scene or resolution");
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  // The nearest lattice site's coordinate, (i + 1/2) dx.
  const auto site = [&](double c) { return (std::lround(c / scene.dx - 0.5) + 0.5) * scene.dx; };
  for (std::size_t a = 0; a < p.size(); ++a) {
    if (!(p.x[a] >= 0 && p.x[a] < scene.box.lx && p.y[a] >= 0 && p.y[a] < scene.box.ly))
      throw ConfigError(path, "'" + file + "': particle " + std::to_string(a) + " at (" + std::to_string(p.x[a]) + ", " +
                                  std::to_string(p.y[a]) + ") lies outside the scene's box [0, " +
                                  std::to_string(scene.box.lx) + ") x [0, " + std::to_string(scene.box.ly) + ")");
    if (p.phase[a] >= static_cast<int>(scene.phase_viscosity.size()))
      throw ConfigError(path, "'" + file + "': particle " + std::to_string(a) + " has phase " + std::to_string(p.phase[a]) +
                                  ", the scene has " + std::to_string(scene.phase_viscosity.size()));
    if (!snap.has_fixed) p.fixed[a] = scene.is_solid(site(p.x[a]), site(p.y[a])) ? 1 : 0;
    x_lo = std::min(x_lo, p.x[a]);
    x_hi = std::max(x_hi, p.x[a]);
    y_lo = std::min(y_lo, p.y[a]);
    y_hi = std::max(y_hi, p.y[a]);
  }
  // The lattice fills the box: its first and last rows and columns lie within one spacing of the box's ends.
  const auto spans = [&](const char* axis, double lo, double hi, double length) {
    if (lo > scene.dx || hi < length - scene.dx)
      throw ConfigError(path, "'" + file + "': the particles span " + axis + " in [" + std::to_string(lo) + ", " +
                                  std::to_string(hi) + "], the scene's box is [0, " + std::to_string(length) +
                                  "): a snapshot of another box");
  };
  spans("y", y_lo, y_hi, scene.box.ly);
  spans("x", x_lo, x_hi, scene.box.lx);
  check_state_against_scene(scene, p, snap.has_fixed, file, path);
  ReferenceFile out;
  out.record = {{"path", file},
                {"bytes", static_cast<std::uintmax_t>(std::filesystem::file_size(file, ec))},
                {"fnv1a64", hex16(fnv1a64_file(file))},
                {"layout", layout_of(file)},
                {"step", step},
                {"time", snap.time},
                {"particles", p.size()},
                {"fixed_from", snap.has_fixed ? "file" : "scene"}};
  out.particles = std::move(p);
  return out;
}

// reference.file: read and checked against the scene now, before anything runs; no transient (it needs the
// direct run's history), no direct run's solver, and the direct_sph switch left on.
void check_reference_file(const json& cell, const json& out, const Scene& scene, const std::string& path) {
  const json& ref = out.at("reference");
  const std::string file = ref.at("file").get<std::string>();
  const json given = cell.contains("reference") && cell["reference"].is_object() ? cell["reference"] : json::object();
  if (file.empty()) {
    if (given.contains("step"))
      throw ConfigError(path + "/reference/step", "a step picks a snapshot of reference.file; no file is given");
    return;
  }
  if (!ref.at("direct_sph").get<bool>())
    throw ConfigError(path + "/reference/direct_sph", "reference.file is the reference; direct_sph false asks for none");
  for (const char* key : {"solver", "observe_spacing_over_eta"})
    if (given.contains(key))
      throw ConfigError(path + "/reference/" + key, "the direct run's parameters are not used with reference.file");
  if (out.contains("transient") && !out.at("transient").at("t_over_tau").empty())
    throw ConfigError(path + "/transient/" + transient_times_key(cell), "transient snapshots need the direct run's history; a reference "
                                                  "read from a file (reference.file) is one state");
  read_reference_file(scene, file, ref.at("step").get<int>(), path + "/reference/file");
}

void mark_untimed_reference(json& row) {
  row["cost"]["speed_up"] = nullptr;
  row["cost"]["speed_up_note"] = "none: the reference was read from a file (reference.file), no direct run was timed";
  row["cost"]["speed_up_cpu"] = nullptr;
  row["cost"]["speed_up_cpu_note"] = row["cost"]["speed_up_note"];
}

}  // namespace closurelab
