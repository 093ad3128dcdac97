#pragma once
// An experiment kind: how one cell of an experiment matrix is validated and run. The runner
// (experiments/runner/runner.hpp) expands the matrix, validates every cell with `resolve` before running any,
// then calls `run` per cell and writes the rows.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"

namespace closurelab {

// Progress lines go to stderr; experiment kinds call this on long runs.
using ProgressFn = std::function<void(const std::string& line)>;

// One top-level key of a cell: a registered strategy or scene (`family` names it; its parameters are listed by
// `closurelab list FAMILY`), or a section with its own parameter schema.
struct KindSection {
  std::string key;
  std::string description;
  std::string family;  // "scene", "kernel", "deconvolver", "quadrature", or empty for a schema section
  ParamSchema params;
};

class ExperimentKind {
 public:
  virtual ~ExperimentKind() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  // Validates one cell (the merged JSON object, found at JSON `path`) and returns it with every default
  // filled in. Throws ConfigError naming the JSON path of anything wrong. Must not run anything costly.
  virtual json resolve(const json& cell, const std::string& path, const Registry& registry) const = 0;
  // The keys a cell may hold, for `closurelab list experiment`.
  virtual std::vector<KindSection> sections() const = 0;
  // Runs a resolved cell. Returns a row object with at least "errors" and "cost" objects and a "status"
  // string ("ok", "no_convergence", "numerical_issue"); the runner adds the resolved parameters.
  virtual json run(const json& resolved, const Registry& registry, const ProgressFn& progress) const = 0;
  // The expected cost of a resolved cell in arbitrary units; only the order matters: the runner hands out the
  // costliest cells first when several run at once, and balances shards by it. Must be cheap. The default
  // (experiment_kinds.cpp): n_y^3 times the model time (solver.target_time in target_time mode, else
  // solver.max_time), from particles ~ n_y^2 at a fixed aspect ratio and steps ~ t / dt with dt ~ h ~ 1/n_y;
  // a factor missing from the cell counts as 1.
  virtual double expected_cost(const json& resolved) const;
  // A stored row's resolved parameters as this version resolves them, so that cells computed before a parameter
  // was renamed or added still match their specs (resume and merge compare them; results_table.hpp). Default: the
  // scene section's (upgraded_scene_params, core/sph/scene.hpp).
  virtual json upgraded_params(json stored) const;
};

// The experiment kinds are a registry family (core/base/registry.hpp: Registry::experiments): the built-ins are
// registered by register_builtin_experiments (experiments/kinds/experiment_kinds.cpp lists them explicitly), a user's
// by `registry.experiments.add(std::make_unique<MyKind>())` in a registration hook
// (experiments/runner/closurelab_main.hpp); `run`, `list` and `merge` then know it like a built-in. A kind is found by
// `registry.experiments.get(name, path)` (ConfigError at `path` naming every known kind).

}  // namespace closurelab
