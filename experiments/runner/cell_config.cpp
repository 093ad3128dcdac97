#include "experiments/runner/cell_config.hpp"

#include <cmath>

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
  return reg.scenes.create(cell.at("scene"), path + "/scene", resolved);
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
