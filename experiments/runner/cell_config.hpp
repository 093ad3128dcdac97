#pragma once
// Shared pieces of experiment-cell validation: the allowed top-level keys, and the scene and kernel
// sub-objects (a kernel's eta defaults to the scene's eta').
#include <memory>
#include <string>
#include <vector>

#include "core/averaging/averaging_kernel.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"

namespace closurelab {

// Throws ConfigError for a key of `cell` not in `allowed`, or when `cell` is not an object.
void check_keys(const json& cell, const std::string& path, const std::vector<std::string>& allowed);

// Resolves and builds the scene at cell["scene"].
std::unique_ptr<Scene> build_scene(const json& cell, const std::string& path, const Registry& reg, json* resolved);

// Resolves and builds the kernel at cell["kernel"] (default {"name": "gaussian"}), eta defaulting to eta'.
std::unique_ptr<AveragingKernel> build_kernel(const json& cell, const std::string& path, const Registry& reg,
                                              double scene_eta, json* resolved);

// Resolves cell[key] against `schema` (a missing key means all defaults).
json resolve_section(const json& cell, const std::string& key, const ParamSchema& schema, const std::string& path);

}  // namespace closurelab
