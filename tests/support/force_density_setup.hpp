#pragma once
// Test helpers of the 2D force-density model's tests (tests/numerical/test_force_density_2d.cpp,
// test_force_density_convective.cpp): a small cylinder lattice with its window and two deconvolvers, the solver
// section resolved from a partial one, and a reproducible random field.
#include <Eigen/Core>
#include <memory>
#include <random>

#include "core/base/registry.hpp"
#include "core/reduced/force_density_2d.hpp"

namespace closurelab::test_support {

struct ForceDensitySetup {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<AveragingKernel> kernel;
  std::unique_ptr<Deconvolver> dv, dn;
};

// cylinder-lattice at n = 32, η' = L/8, a = 0.2 L, with `scene_extra` over it; the window at the scene's η'.
inline ForceDensitySetup cylinder_lattice_setup(const json& scene_extra = json::object(),
                                                const json& deconvolver = json{{"name", "tikhonov"}}) {
  const Registry& reg = builtin_registry();
  json s = {{"name", "cylinder-lattice"}, {"n", 32}, {"eta_over_l", 0.125}, {"radius_over_length", 0.2}};
  s.update(scene_extra);
  ForceDensitySetup out;
  out.scene = reg.scenes.create(reg.scenes.resolve(s, "/scene"), "/scene");
  out.kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", out.scene->eta}}, "/kernel");
  const json d = reg.deconvolvers.resolve(deconvolver, "/d");
  out.dv = reg.deconvolvers.create(d, "/d");
  out.dn = reg.deconvolvers.create(d, "/d");
  return out;
}

inline ForceDensity2DOptions force_density_options(const json& solver = json::object()) {
  return force_density_2d_options_from(resolve_params(solver, force_density_2d_schema(), "/solver", {}));
}

// n values uniform in [−1, 1) from a Mersenne twister seeded with `seed`.
inline Eigen::VectorXd random_field(Eigen::Index n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k) x[k] = u(gen);
  return x;
}

}  // namespace closurelab::test_support
