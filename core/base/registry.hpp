#pragma once
// The strategy registry (DESIGN.md §3): families of named entries, each with a description, a parameter
// schema and a factory taking validated (resolved) JSON. Filled explicitly by register_builtin_strategies().
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/base/errors.hpp"
#include "core/base/params.hpp"

namespace closurelab {

struct EntryInfo {
  std::string name;
  std::string description;
  ParamSchema params;
};

class FamilyBase {
 public:
  virtual ~FamilyBase() = default;
  virtual std::vector<EntryInfo> entries() const = 0;
  virtual const std::string& family_name() const = 0;
};

template <class T>
class Family : public FamilyBase {
 public:
  using Factory = std::function<std::unique_ptr<T>(const json& resolved)>;
  explicit Family(std::string name) : name_(std::move(name)) {}

  // A name is registered once: a second registration under the same name is a programming error (it would
  // otherwise silently replace the first entry), reported as std::logic_error naming the family and the name.
  void add(EntryInfo info, Factory factory) {
    const std::string key = info.name;
    if (entries_.count(key))
      throw std::logic_error("registry: " + name_ + " '" + key + "' is registered twice");
    entries_.emplace(key, Item{std::move(info), std::move(factory)});
  }
  bool contains(const std::string& name) const { return entries_.count(name) > 0; }

  const EntryInfo& info(const std::string& name, const std::string& path = "") const { return find(name, path).info; }

  // Validates `config` ({"name": ..., params...}) found at JSON `path` and returns the resolved parameters.
  json resolve(const json& config, const std::string& path) const {
    const auto& item = find(name_of(config, path), path + "/name");
    json r = resolve_params(config, item.info.params, path);
    r["name"] = item.info.name;
    return r;
  }
  // Builds an instance from `config`; the resolved parameters are written to `resolved_out` if given.
  std::unique_ptr<T> create(const json& config, const std::string& path, json* resolved_out = nullptr) const {
    json r = resolve(config, path);
    std::unique_ptr<T> obj;
    try {
      obj = find(r.at("name").get<std::string>(), path).factory(r);
    } catch (const ConfigError& e) {
      throw ConfigError(path + e.path(), e.message());  // factories report paths relative to their object
    }
    if (resolved_out) *resolved_out = r;
    return obj;
  }

  std::vector<EntryInfo> entries() const override {
    std::vector<EntryInfo> v;
    for (const auto& [k, item] : entries_) v.push_back(item.info);
    return v;
  }
  const std::string& family_name() const override { return name_; }
  std::string known_names() const {
    std::string s;
    for (const auto& [k, item] : entries_) s += (s.empty() ? "" : ", ") + k;
    return s;
  }

 private:
  struct Item {
    EntryInfo info;
    Factory factory;
  };
  std::string name_of(const json& config, const std::string& path) const {
    if (config.is_string()) return config.get<std::string>();
    if (!config.is_object()) throw ConfigError(path, "expected an object with a \"name\" for the " + name_ + " family");
    if (!config.contains("name") || !config.at("name").is_string())
      throw ConfigError(path + "/name", "missing string \"name\"; known " + name_ + " names: " + known_names());
    return config.at("name").get<std::string>();
  }
  const Item& find(const std::string& name, const std::string& path) const {
    auto it = entries_.find(name);
    if (it == entries_.end())
      throw ConfigError(path, "unknown " + name_ + " '" + name + "'; known: " + known_names());
    return it->second;
  }
  std::string name_;
  std::map<std::string, Item> entries_;
};

// A family of named, stateless objects held whole, in the order registered (the experiment kinds: each has
// name(); `closurelab list experiment` prints them with their sections). As for a Family, a name is registered once:
// a second registration is a std::logic_error naming it.
template <class T>
class InstanceFamily {
 public:
  explicit InstanceFamily(std::string name) : name_(std::move(name)) {}
  void add(std::shared_ptr<const T> item) {
    if (!item) throw std::logic_error("registry: " + name_ + " needs an object");
    const std::string key = item->name();
    if (contains(key)) throw std::logic_error("registry: " + name_ + " '" + key + "' is registered twice");
    items_.push_back(std::move(item));
  }
  bool contains(const std::string& name) const {
    for (const auto& item : items_)
      if (item->name() == name) return true;
    return false;
  }
  // The entry called `name`; ConfigError at `path` naming every known entry otherwise.
  const T& get(const std::string& name, const std::string& path) const {
    for (const auto& item : items_)
      if (item->name() == name) return *item;
    throw ConfigError(path, "unknown " + name_ + " '" + name + "'; known: " + known_names());
  }
  std::vector<const T*> all() const {
    std::vector<const T*> v;
    for (const auto& item : items_) v.push_back(item.get());
    return v;
  }
  const std::string& family_name() const { return name_; }
  std::string known_names() const {
    std::string s;
    for (const auto& item : items_) s += (s.empty() ? "" : ", ") + item->name();
    return s;
  }

 private:
  std::string name_;
  std::vector<std::shared_ptr<const T>> items_;
};

class AveragingKernel;
class Deconvolver;
class StressQuadrature;
class Integrator;
struct Scene;
class ExperimentKind;

struct Registry {
  Family<AveragingKernel> kernels{"kernel"};
  Family<Deconvolver> deconvolvers{"deconvolver"};
  Family<StressQuadrature> quadratures{"quadrature"};
  Family<Scene> scenes{"scene"};
  // How a stepped reduced model advances (core/reduced/integrator.hpp), named by its solver.time_integration.
  Family<Integrator> integrators{"integrator"};
  // The experiment kinds (experiments/kinds/experiment_kind.hpp): the built-ins by register_builtin_experiments
  // (experiments/kinds/experiment_kinds.cpp), then a user's, added by a registration hook with
  // `registry.experiments.add(...)`. The runner finds every cell's kind here.
  InstanceFamily<ExperimentKind> experiments{"experiment kind"};

  // The strategy and scene families (parameter schemas; `closurelab list` prints the experiment kinds apart, with
  // their sections).
  std::vector<const FamilyBase*> families() const { return {&kernels, &deconvolvers, &quadratures, &scenes, &integrators}; }
};

// Fills `registry` with every built-in strategy and scene (strategies/register_builtin.cpp). Idempotent: a
// registry that already holds the built-ins is left as it is.
void register_builtin_strategies(Registry& registry);

// Fills `registry` with every built-in experiment kind (experiments/kinds/experiment_kinds.cpp, in the closurelab_runner
// library). Idempotent, as register_builtin_strategies.
void register_builtin_experiments(Registry& registry);

// A process-wide registry of every built-in strategy, scene and experiment kind (tests, benchmarks; defined with the
// experiment kinds); the command line builds its own (closurelab_main), the user's entries after the built-ins.
const Registry& builtin_registry();

}  // namespace closurelab
