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

// Resolves and builds the scene at cell["scene"], then checks its scales (check_scene_scales).
std::unique_ptr<Scene> build_scene(const json& cell, const std::string& path, const Registry& reg, json* resolved);

// Refuses (ConfigError at `path`, the scene's JSON path) a scene whose physical scales leave [1e-100, 1e100]:
// density, each viscosity, lattice spacing, sound speed, and the spacing's viscous time rho dx^2 / mu_max.
// The engine multiplies up to three of them (pressure rho c^2, the viscous term mu v / dx^2), so within that range
// every intermediate stays a normal double; outside, the particles' velocities fall into denormals (mu = 1e300
// ended `converged` at 22 % error with t = 2e-300) or the pressure underflows to 0 (rho = 1e-300).
void check_scene_scales(const Scene& scene, const std::string& path);

// Resolves and builds the kernel at cell["kernel"] (default {"name": "gaussian"}), eta defaulting to eta'.
std::unique_ptr<AveragingKernel> build_kernel(const json& cell, const std::string& path, const Registry& reg,
                                              double scene_eta, json* resolved);

// Resolves cell[key] against `schema` (a missing key means all defaults).
json resolve_section(const json& cell, const std::string& key, const ParamSchema& schema, const std::string& path);

}  // namespace closurelab
