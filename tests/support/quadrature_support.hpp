#pragma once
// Shared fixtures of the stress-quadrature tests: scenes, node meshes, velocity samplers and comparisons.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "core/averaging/averaging.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/closure/stress_quadrature.hpp"

namespace closurelab::quadrature_test {

inline std::unique_ptr<Scene> channel(int ny, double eta_over_ly = 1.0 / 16, int nx = 12,
                                      const std::string& walls = "zero_velocity") {
  return builtin_registry().scenes.create(
      json{{"name", "poiseuille-uniform"}, {"n_y", ny}, {"n_x", nx}, {"eta_over_ly", eta_over_ly}, {"wall_model", walls}},
      "/scene");
}

// A fully periodic, wall-free n x n lattice (not x-invariant), two-phase viscosity field off by default.
inline Scene periodic_box(int n, double length) {
  Scene s;
  s.name = "periodic-test";
  s.nx = s.ny = n;
  s.dx = length / n;
  s.box = PeriodicBox{length, length, true, true};
  s.has_walls = false;
  s.x_invariant = false;
  s.force_x = [](double) { return 0.0; };
  s.h = s.dx;
  s.sound_speed = 1.0;
  s.background_pressure = 0.5;
  s.phase_viscosity = {1.5};
  return s;
}

// A sampler from a velocity function; points inside the scene's walls come back at rest.
inline VelocitySampler sampler_of(const Scene& s, std::function<Vec2(const Vec2&)> v) {
  return [&s, v](const std::vector<Vec2>& pts) {
    Eigen::Matrix2Xd out(2, pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) out.col(k) = s.is_wall(pts[k].y()) ? Vec2::Zero() : v(pts[k]);
    return out;
  };
}

// max over components and nodes of |a − b|, and max |b| (the scale).
inline std::pair<double, double> max_difference(const std::map<std::string, Eigen::VectorXd>& a,
                                                const std::map<std::string, Eigen::VectorXd>& b) {
  double diff = 0.0, scale = 0.0;
  for (const auto& [c, field] : b) {
    diff = std::max(diff, (a.at(c) - field).cwiseAbs().maxCoeff());
    scale = std::max(scale, field.cwiseAbs().maxCoeff());
  }
  return {diff, scale};
}

}  // namespace closurelab::quadrature_test
