#pragma once
// The strategy registry (DESIGN.md §3): families of named entries, each with a description, a parameter
// schema and a factory taking validated (resolved) JSON. Filled explicitly by register_builtin_strategies().
#include <functional>
#include <map>
#include <memory>
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

class AveragingKernel;
class Deconvolver;
class StressQuadrature;
struct Scene;
class ExperimentKind;

struct Registry {
  Family<AveragingKernel> kernels{"kernel"};
  Family<Deconvolver> deconvolvers{"deconvolver"};
  Family<StressQuadrature> quadratures{"quadrature"};
  Family<Scene> scenes{"scene"};
  // Experiment kinds beyond the built-ins, added by a user's registration hook with add_experiment_kind
  // (experiments/kinds/experiment_kind.hpp; an experiment kind is a stateless object, held here whole). The
  // runner finds a kind here or among the built-ins (find_experiment_kind with the registry).
  std::vector<std::shared_ptr<const ExperimentKind>> experiment_kinds;

  std::vector<const FamilyBase*> families() const { return {&kernels, &deconvolvers, &quadratures, &scenes}; }
};

// Fills `registry` with every built-in strategy and scene (strategies/register_builtin.cpp). Idempotent: a
// registry that already holds the built-ins is left as it is.
void register_builtin_strategies(Registry& registry);

// A process-wide registry of the built-ins (tests, benchmarks); the command line builds its own (closurelab_main).
const Registry& builtin_registry();

}  // namespace closurelab
