#include "experiments/kinds/cell_config.hpp"

#include <cmath>
#include <sstream>

#include "core/base/errors.hpp"

namespace closurelab {

void check_keys(const json& cell, const std::string& path, const std::vector<std::string>& allowed) {
  if (!cell.is_object()) throw ConfigError(path, "a cell must be a JSON object");
  for (const auto& [k, v] : cell.items()) {
    if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw ConfigError(path + "/" + k, "unknown key; allowed keys: " + list);
  }
}

std::unique_ptr<Scene> build_scene(const json& cell, const std::string& path, const Registry& reg, json* resolved) {
  if (!cell.contains("scene")) throw ConfigError(path + "/scene", "missing scene; known: " + reg.scenes.known_names());
  auto scene = reg.scenes.create(cell.at("scene"), path + "/scene", resolved);
  check_scene_scales(*scene, path + "/scene");
  return scene;
}

void check_scene_scales(const Scene& s, const std::string& path) {
  constexpr double lo = 1e-100, hi = 1e100;
  const auto check = [&](const std::string& key, const std::string& what, double v) {
    if (v >= lo && v <= hi) return;
    std::ostringstream os;
    os << what << " is " << v << ", outside [1e-100, 1e100]: the engine's products of such scales (pressure, "
       << "viscous force, time step) leave the normal double range, so velocities would lose their digits; "
       << "rescale the problem (model units: rho = mu = L_y = 1)";
    throw ConfigError(path + key, os.str());
  };
  check(s.params.contains("rho") ? "/rho" : "", "the density", s.rho0);
  for (double mu : s.phase_viscosity) check(s.params.contains("mu") ? "/mu" : "", "a viscosity", mu);
  check("", "the lattice spacing", s.dx);
  if (s.sound_speed != 0.0) check("", "the sound speed", s.sound_speed);
  check("", "the viscous time of the spacing rho dx^2 / mu_max", s.rho0 * s.dx * s.dx / s.max_viscosity());
}

std::unique_ptr<AveragingKernel> build_kernel(const json& cell, const std::string& path, const Registry& reg,
                                              double scene_eta, json* resolved) {
  json k = cell.contains("kernel") ? cell.at("kernel") : json{{"name", "gaussian"}};
  if (k.is_string()) k = json{{"name", k}};
  // One η': the scene's. A kernel may repeat it, but a different value is a conflicting spec.
  if (k.is_object() && k.contains("eta")) {
    const json& e = k.at("eta");
    if (!e.is_number() || std::abs(e.get<double>() - scene_eta) > 1e-12 * scene_eta)
      throw ConfigError(path + "/kernel/eta", "eta' is the scene's (" + std::to_string(scene_eta) +
                                                  " here); leave it out of the kernel or give the same value");
  }
  if (k.is_object()) k["eta"] = scene_eta;
  return reg.kernels.create(k, path + "/kernel", resolved);
}

json resolve_section(const json& cell, const std::string& key, const ParamSchema& schema, const std::string& path) {
  return resolve_params(cell.contains(key) ? cell.at(key) : json(), schema, path + "/" + key, {});
}

}  // namespace closurelab
