#include "core/base/params.hpp"


#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "core/base/errors.hpp"
#include "core/base/json_reader.hpp"

namespace closurelab {


ParamSpec number_param(std::string name, json def, std::string description, std::optional<double> min,
                       std::optional<double> max, bool exclusive_min) {
  return ParamSpec{std::move(name), ParamType::Number, std::move(def), std::move(description), min, max, exclusive_min};
}
ParamSpec integer_param(std::string name, json def, std::string description, std::optional<double> min,
                        std::optional<double> max, IntegerKind kind) {
  ParamSpec p{std::move(name), ParamType::Integer, std::move(def), std::move(description), min, max};
  p.integer_kind = kind;
  return p;
}
ParamSpec string_param(std::string name, json def, std::string description, std::vector<std::string> choices) {
  ParamSpec p{std::move(name), ParamType::String, std::move(def), std::move(description)};
  p.choices = std::move(choices);
  return p;
}
ParamSpec bool_param(std::string name, bool def, std::string description) {
  return ParamSpec{std::move(name), ParamType::Boolean, def, std::move(description)};
}
ParamSpec object_param(std::string name, json def, std::string description) {
  return ParamSpec{std::move(name), ParamType::Object, std::move(def), std::move(description)};
}
ParamSpec array_param(std::string name, json def, std::string description) {
  return ParamSpec{std::move(name), ParamType::Array, std::move(def), std::move(description)};
}
ParamSpec entry_param(std::string name, json def, std::string description) {
  return ParamSpec{std::move(name), ParamType::Entry, std::move(def), std::move(description)};
}

std::string to_string(ParamType t) {
  switch (t) {
    case ParamType::Integer: return "integer";
    case ParamType::Number: return "number";
    case ParamType::String: return "string";
    case ParamType::Boolean: return "boolean";
    case ParamType::Object: return "object";
    case ParamType::Array: return "array";
    case ParamType::Entry: return "name or object";
  }
  return "?";
}

namespace {

bool type_matches(const json& v, ParamType t) {
  switch (t) {
    case ParamType::Integer: return v.is_number_integer();
    case ParamType::Number: return v.is_number();
    case ParamType::String: return v.is_string();
    case ParamType::Boolean: return v.is_boolean();
    case ParamType::Object: return v.is_object();
    case ParamType::Array: return v.is_array();
    case ParamType::Entry: return v.is_string() || (v.is_object() && v.contains("name") && v.at("name").is_string());
  }
  return false;
}

// The value of an Integer parameter must fit the type it is read into (json holds up to 64 bits; a get<int>()
// of 2^32 would silently give 0). Compared as integers, not doubles (2^63 - 1 is not a double).
void check_integer_width(const json& v, IntegerKind kind, const std::string& at) {
  std::int64_t lo = 0;
  std::uint64_t hi = std::numeric_limits<std::uint64_t>::max();
  const char* type = "uint64";
  if (kind == IntegerKind::int32) {
    lo = std::numeric_limits<std::int32_t>::min();
    hi = static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max());
    type = "32-bit signed integer";
  } else if (kind == IntegerKind::int64) {
    lo = std::numeric_limits<std::int64_t>::min();
    hi = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    type = "64-bit signed integer";
  } else {
    type = "64-bit unsigned integer";
  }
  const bool fits = v.is_number_unsigned() ? v.get<std::uint64_t>() <= hi
                                           : (v.get<std::int64_t>() >= lo &&
                                              (v.get<std::int64_t>() < 0 || static_cast<std::uint64_t>(v.get<std::int64_t>()) <= hi));
  if (!fits)
    throw ConfigError(at, "value " + v.dump() + " does not fit a " + type + " (allowed " + std::to_string(lo) + " to " +
                              std::to_string(hi) + ")");
}

std::string allowed_keys(const ParamSchema& schema) {
  std::string s;
  for (const auto& p : schema) s += (s.empty() ? "" : ", ") + p.name;
  return s.empty() ? "(none)" : s;
}

// Earlier names of parameters, read as their current name wherever a schema has the current name and not the
// earlier one: the averaging width was eta_over_ly on the channels and kolmogorov (eta_over_l on every scene now), so
// committed specs and stored rows that say eta_over_ly still read.
const std::vector<std::pair<std::string, std::string>>& earlier_names() {
  static const std::vector<std::pair<std::string, std::string>> v = {{"eta_over_ly", "eta_over_l"}};
  return v;
}

bool in_schema(const ParamSchema& schema, const std::string& name) {
  for (const auto& p : schema)
    if (p.name == name) return true;
  return false;
}

// `given` with every earlier name its schema knows under its current name; both names given is an error.
json with_current_names(const json& given, const ParamSchema& schema, const std::string& path) {
  if (!given.is_object()) return given;
  json out = given;
  for (const auto& [earlier, current] : earlier_names()) {
    if (!out.contains(earlier) || in_schema(schema, earlier) || !in_schema(schema, current)) continue;
    if (out.contains(current))
      throw ConfigError(path + "/" + earlier, "an earlier name of " + current + ", which is given too; give one");
    out[current] = out[earlier];
    out.erase(earlier);
  }
  return out;
}

}  // namespace

json resolve_params(const json& given_as_written, const ParamSchema& schema, const std::string& path,
                    const std::vector<std::string>& passthrough) {
  const json given = with_current_names(given_as_written, schema, path);
  if (!given.is_null() && !given.is_object())
    throw ConfigError(path, "expected an object, got " + std::string(given.type_name()));
  json out = json::object();
  if (given.is_object()) {
    for (const auto& [key, value] : given.items()) {
      bool known = false;
      for (const auto& p : schema) known = known || p.name == key;
      for (const auto& k : passthrough) known = known || k == key;
      if (!known) throw ConfigError(path + "/" + key, "unknown key; allowed keys: " + allowed_keys(schema));
      if (std::find(passthrough.begin(), passthrough.end(), key) != passthrough.end()) out[key] = value;
    }
  }
  for (const auto& p : schema) {
    const std::string at = path + "/" + p.name;
    json v;
    if (given.is_object() && given.contains(p.name)) {
      v = given.at(p.name);
    } else if (p.default_value.is_null()) {
      throw ConfigError(at, "required parameter is missing (" + p.description + ")");
    } else {
      v = p.default_value;
    }
    if (!type_matches(v, p.type))
      throw ConfigError(at, "expected " +
                                (p.type == ParamType::Entry ? std::string("a name or an object with a string \"name\"")
                                                            : to_string(p.type)) +
                                ", got " + std::string(v.type_name()) + " (" + v.dump() + ")");
    if (p.type == ParamType::Integer) check_integer_width(v, p.integer_kind, at);
    if (p.type == ParamType::Number || p.type == ParamType::Integer) {
      const double x = v.get<double>();
      if (!std::isfinite(x)) throw ConfigError(at, "must be finite");
      if (p.min && (p.exclusive_min ? !(x > *p.min) : !(x >= *p.min)))
        throw ConfigError(at, "value " + v.dump() + " must be " + (p.exclusive_min ? "> " : ">= ") + json(*p.min).dump());
      if (p.max && !(x <= *p.max)) throw ConfigError(at, "value " + v.dump() + " must be <= " + json(*p.max).dump());
    }
    if (p.type == ParamType::String && !p.choices.empty()) {
      const auto s = v.get<std::string>();
      if (std::find(p.choices.begin(), p.choices.end(), s) == p.choices.end()) {
        std::string c;
        for (const auto& ch : p.choices) c += (c.empty() ? "" : ", ") + ch;
        throw ConfigError(at, "'" + s + "' is not one of: " + c);
      }
    }
    out[p.name] = v;
  }
  return out;
}

json schema_to_json(const ParamSchema& schema) {
  json a = json::array();
  for (const auto& p : schema) {
    json e = {{"name", p.name}, {"type", to_string(p.type)}, {"default", p.default_value}, {"description", p.description}};
    if (p.min) e["min"] = *p.min;
    if (p.max) e["max"] = *p.max;
    if (p.exclusive_min) e["exclusive_min"] = true;
    if (!p.choices.empty()) e["choices"] = p.choices;
    a.push_back(e);
  }
  return a;
}

json read_json_file(const std::string& file) { return read_json_file_guarded(file); }

double require_finite(double x, const std::string& what) {
  if (!std::isfinite(x)) throw NumericalError(what + " is not finite");
  return x;
}

}  // namespace closurelab
