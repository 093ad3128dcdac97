// The experiment matrix: expansion of a spec into cells and their validation (running them: run_experiment.cpp).
#include "experiments/runner/runner.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/spec_checks.hpp"

namespace closurelab {

namespace {

// FNV-1a with an offset basis one digit short of the standard 14695981039346656037 (reference_store.hpp's
// fnv1a64): kept as it is, since it names every committed cell file (ids are the resume and merge keys).
std::string fnv1a_hex(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return std::string(buf, 12);
}

// Whether `value` (an object) names a strategy other than the one `slot` holds: {"name": ...} differing.
bool names_another_strategy(const json& slot, const json& value) {
  return value.is_object() && value.contains("name") && slot.is_object() && slot.value("name", json()) != value.at("name");
}

// Sets `value` into `slot`: an object merges key by key (deep merge) unless it names another strategy, which
// replaces the object there; anything else replaces.
void merge_value(json& slot, const json& value) {
  if (!value.is_object() || !slot.is_object() || names_another_strategy(slot, value)) {
    slot = value;
    return;
  }
  for (const auto& [k, v] : value.items()) {
    if (slot.contains(k))
      merge_value(slot[k], v);
    else
      slot[k] = v;
  }
}

std::string value_label(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// The number of cells, counted (in double) before any is made: expanding 10^6 cells took 4 GB and 38 s, 10^12
// ran out of memory inside --dry-run. Refused above max_cells() (memory_limit.hpp) with the count.
void check_cell_count(const json& spec) {
  double product = 1.0;
  std::string factors;
  if (spec.contains("axes") && spec["axes"].is_object())
    for (const auto& [key, values] : spec["axes"].items())
      if (values.is_array() && !values.empty()) {
        product *= static_cast<double>(values.size());
        factors += (factors.empty() ? "" : " x ") + std::to_string(values.size());
      }
  if (spec.contains("cells") && spec["cells"].is_array() && !spec["cells"].empty()) {
    product *= static_cast<double>(spec["cells"].size());
    factors += (factors.empty() ? "" : " x ") + std::to_string(spec["cells"].size()) + " cells";
  }
  const double limit = static_cast<double>(max_cells());
  if (product > limit) {
    char count[32];
    std::snprintf(count, sizeof count, product < 1e15 ? "%.0f" : "%.3g", product);
    throw ConfigError(spec.contains("axes") ? "/axes" : "/cells",
                      std::string("the matrix has ") + count + " cells (" + factors + "), above the cell limit of " +
                          std::to_string(max_cells()) + " (" + max_cells_source() + "); expanding it would take about " +
                          format_bytes(product * 4000.0) + " (4 kB per cell measured) before any cell runs");
  }
}

}  // namespace

void set_dotted(json& target, const std::string& dotted, const json& value, const std::string& path) {
  json* node = &target;
  std::stringstream ss(dotted);
  std::string part, next;
  std::getline(ss, part, '.');
  while (std::getline(ss, next, '.')) {
    if (part.empty()) throw ConfigError(path, "empty component in dotted key '" + dotted + "'");
    if (!node->contains(part)) (*node)[part] = json::object();
    node = &(*node)[part];
    if (!node->is_object()) throw ConfigError(path, "'" + part + "' in '" + dotted + "' is not an object");
    part = next;
  }
  // An object merges into the object it lands on (deep merge: the base's other keys stay), unless it names a
  // different strategy ("name"), whose parameters would not fit the base's: then it replaces it (at any depth).
  merge_value((*node)[part], value);
}

namespace {

bool starts_with_key(const std::string& key, const std::string& prefix) {
  return key.size() > prefix.size() && key.compare(0, prefix.size(), prefix) == 0 && key[prefix.size()] == '.';
}

// The value at dotted `key` inside `v`, or null.
json dotted_value(const json& v, const std::string& key) {
  const json* node = &v;
  std::stringstream ss(key);
  std::string part;
  while (std::getline(ss, part, '.')) {
    if (!node->is_object() || !node->contains(part)) return nullptr;
    node = &node->at(part);
  }
  return *node;
}

// Sets `key` to `value` in one value of an axis or cell that the spec gives for `given` (a dotted key); a value
// the spec gave there, other than `value`, is said in `replaced` (`where` names the axis value or cell).
void override_in(json& given_value, const std::string& given, const std::string& key, const json& value,
                 const std::string& path, const std::string& where, std::vector<std::string>& replaced) {
  if (given == key) {
    if (given_value != value) replaced.push_back(where + " gave " + key + " = " + given_value.dump());
    given_value = value;
  } else if (starts_with_key(key, given)) {
    if (!given_value.is_object())
      throw ConfigError(path, "--set " + key + ": this value of '" + given + "' is not an object");
    const json before = dotted_value(given_value, key.substr(given.size() + 1));
    if (!before.is_null() && before != value) replaced.push_back(where + " gave " + key + " = " + before.dump());
    set_dotted(given_value, key.substr(given.size() + 1), value, path);
  } else if (starts_with_key(given, key)) {
    throw ConfigError(path, "--set " + key + " sets what '" + given +
                                "' varies inside it; set the inner key instead, or remove it from the spec");
  }
}

}  // namespace

std::vector<std::string> apply_override(json& spec, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("", "--set needs KEY=VALUE with a dotted KEY (e.g. solver.kappa=0.1), got '" + assignment + "'");
  const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  json value = json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;  // not JSON: a string
  if (!spec.is_object()) throw ConfigError("", "an experiment spec must be a JSON object");
  if (!spec.contains("base")) spec["base"] = json::object();
  if (!spec["base"].is_object()) throw ConfigError("/base", "expected an object");
  std::vector<std::string> replaced;
  set_dotted(spec["base"], key, value, "--set " + key);
  if (spec.contains("axes") && spec["axes"].is_object()) {
    for (auto& [axis, values] : spec["axes"].items()) {
      if (axis == key) {
        if (values != json::array({value}))
          replaced.push_back("the axis " + key + " over " + values.dump() + " is the one value " + value.dump() +
                             (values.is_array() && values.size() > 1
                                  ? " (the matrix has " + std::to_string(values.size()) + " times fewer cells)"
                                  : ""));
        values = json::array({value});  // one value left: the axis still labels the cells
      } else if (values.is_array()) {
        for (std::size_t i = 0; i < values.size(); ++i)
          override_in(values[i], axis, key, value, "/axes/" + axis + "/" + std::to_string(i),
                      "the axis " + axis + "'s value " + std::to_string(i), replaced);
      }
    }
  }
  if (spec.contains("cells") && spec["cells"].is_array()) {
    for (std::size_t i = 0; i < spec["cells"].size(); ++i) {
      json& cell = spec["cells"][i];
      if (!cell.is_object()) continue;  // expand_matrix reports it
      for (auto& [given, v] : cell.items())
        if (given != "label")
          override_in(v, given, key, value, "/cells/" + std::to_string(i) + "/" + given,
                      "cell " + std::to_string(i), replaced);
    }
  }
  return replaced;
}

namespace {

// A null given in a spec (the base, an axis value, a cell's key) would reset what it lands on to the defaults (a
// cell's "solver": null dropped the base's solver section): refused, with what to write instead.
void refuse_null(const json& v, const std::string& path) {
  if (v.is_null())
    throw ConfigError(path, "null is not a value here: leave the key out to keep the base's (or the default), or give "
                            "the value");
  if (v.is_object())
    for (const auto& [k, inner] : v.items()) refuse_null(inner, path + "/" + k);
}

// The dotted keys of the leaves `value` sets when given at dotted `key` (an object's keys flattened; an array or a
// scalar is a leaf).
void leaves_of(const json& value, const std::string& key, std::vector<std::string>& out) {
  if (value.is_object() && !value.empty()) {
    for (const auto& [k, inner] : value.items()) leaves_of(inner, key + "." + k, out);
  } else {
    out.push_back(key);
  }
}

// One key set twice in one group of given keys (a cell's keys, or the axes): once dotted and once inside an object
// ({"solver": {"kappa": 0.1}, "solver.kappa": 0.2}), which one applied was decided by the keys' order. Refused at
// the second.
void refuse_twice_given(const std::vector<std::pair<std::string, std::vector<json>>>& given, const std::string& at) {
  std::map<std::string, std::string> by_leaf;  // leaf -> the given key that sets it
  for (const auto& [key, values] : given) {
    std::vector<std::string> leaves;
    for (const json& v : values) leaves_of(v, key, leaves);
    for (const std::string& leaf : leaves) {
      const auto [it, fresh] = by_leaf.emplace(leaf, key);
      if (!fresh && it->second != key)
        throw ConfigError(at + "/" + key, "sets " + leaf + ", which '" + it->second +
                                              "' sets too: give each key once (dotted or inside its object, not both)");
    }
  }
}

}  // namespace

std::vector<MatrixCell> expand_matrix(const json& spec) {
  if (!spec.is_object()) throw ConfigError("", "an experiment spec must be a JSON object");
  for (const auto& [k, v] : spec.items()) {
    static const std::vector<std::string> allowed = {"name", "kind", "description", "base", "axes", "cells"};
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      throw ConfigError("/" + k, "unknown key; allowed keys: name, kind, description, base, axes, cells");
  }
  check_spec_top_level(spec);
  const json base = spec.value("base", json::object());
  if (!base.is_object()) throw ConfigError("/base", "expected an object");
  refuse_null(base, "/base");
  {
    std::vector<std::pair<std::string, std::vector<json>>> given;
    for (const auto& [k, v] : base.items()) given.push_back({k, {v}});
    refuse_twice_given(given, "/base");
  }

  check_cell_count(spec);
  // Cartesian product of the axes (keys in sorted order, values in the listed order).
  std::vector<std::pair<json, std::string>> combos = {{base, ""}};
  if (spec.contains("axes")) {
    const json& axes = spec["axes"];
    if (!axes.is_object()) throw ConfigError("/axes", "expected an object of dotted keys to value lists");
    std::vector<std::pair<std::string, std::vector<json>>> given;
    for (const auto& [key, values] : axes.items()) {
      if (!values.is_array()) continue;  // reported below
      for (std::size_t i = 0; i < values.size(); ++i) refuse_null(values[i], "/axes/" + key + "/" + std::to_string(i));
      given.push_back({key, values.get<std::vector<json>>()});
    }
    refuse_twice_given(given, "/axes");
    for (const auto& [key, values] : axes.items()) {
      const std::string at = "/axes/" + key;
      if (!values.is_array() || values.empty()) throw ConfigError(at, "expected a non-empty array of values");
      std::vector<std::pair<json, std::string>> next;
      for (const auto& [cfg, label] : combos) {
        for (const auto& v : values) {
          json c = cfg;
          set_dotted(c, key, v, at);
          next.emplace_back(c, label + (label.empty() ? "" : ", ") + key + "=" + value_label(v));
        }
      }
      combos = std::move(next);
    }
  }
  std::vector<MatrixCell> cells;
  const bool has_axes = spec.contains("axes");
  if (spec.contains("cells")) {
    const json& list = spec["cells"];
    if (!list.is_array()) throw ConfigError("/cells", "expected an array of cell objects");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = "/cells/" + std::to_string(i);
      if (!list[i].is_object()) throw ConfigError(at, "expected an object");
      std::vector<std::pair<std::string, std::vector<json>>> given;
      for (const auto& [k, v] : list[i].items()) {
        if (k == "label") continue;
        refuse_null(v, at + "/" + k);
        given.push_back({k, {v}});
      }
      refuse_twice_given(given, at);
      for (const auto& [cfg, label] : (has_axes ? combos : std::vector<std::pair<json, std::string>>{{base, ""}})) {
        json c = cfg;
        std::string cell_label = label;
        for (const auto& [k, v] : list[i].items()) {
          if (k == "label") {
            if (!v.is_string()) throw ConfigError(at + "/label", "expected a string");
            cell_label = v.get<std::string>() + (label.empty() ? "" : ", " + label);
            continue;
          }
          set_dotted(c, k, v, at + "/" + k);
        }
        cells.push_back({"", cell_label, at, c});
      }
    }
  } else {
    for (std::size_t i = 0; i < combos.size(); ++i)
      cells.push_back({"", combos[i].second, has_axes ? "/axes[" + std::to_string(i) + "]" : "/base", combos[i].first});
  }
  for (auto& c : cells) {
    c.id = fnv1a_hex(spec["kind"].get<std::string>() + c.config.dump());
    if (c.label.empty()) c.label = c.id;
  }
  check_distinct_cells(cells);
  return cells;
}

std::optional<ValidMatrix> validate_matrix(const json& spec, const Registry& registry) {
  ValidMatrix m;
  try {
    m.cells = expand_matrix(spec);
    m.kind = &registry.experiments.get(spec["kind"].get<std::string>(), "/kind");
  } catch (const ConfigError& e) {
    std::cerr << "error: invalid experiment spec: " << e.what() << "\n";
    return std::nullopt;
  }
  std::vector<std::string> problems;
  for (const auto& c : m.cells) {
    try {
      m.resolved.push_back(m.kind->resolve(c.config, c.path, registry));
      m.costs.push_back(m.kind->expected_cost(m.resolved.back()));
    } catch (const ConfigError& e) {
      problems.push_back(std::string(e.what()) + "  [cell " + c.label + "]");
    }
  }
  if (problems.empty()) return m;
  for (const auto& p : problems) std::cerr << "error: " << p << "\n";
  std::cerr << "error: " << problems.size() << " invalid cell(s); nothing was run\n";
  return std::nullopt;
}

}  // namespace closurelab
