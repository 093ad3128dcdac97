#pragma once
// Parameter schemas: every registered strategy, scene and experiment kind declares its parameters
// (name, type, default, range, meaning); `resolve_params` validates a JSON object against a schema,
// fills defaults and reports errors by JSON path (DESIGN.md §3).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace closurelab {

using json = nlohmann::json;

// Entry: a registered strategy named by a string, or an object {"name": ..., its parameters...} (e.g. the solver's
// time_integration); only that shape is checked here, the entry's own schema where the registry is known.
enum class ParamType { Integer, Number, String, Boolean, Object, Array, Entry };
// The C++ type an Integer parameter is read into: its range bounds the value whatever min/max say (a value
// that does not fit is an error naming the path, never a silent truncation).
enum class IntegerKind { int32, int64, uint64 };

struct ParamSpec {
  std::string name;
  ParamType type;
  json default_value;                  // null = required
  std::string description;
  std::optional<double> min{};         // inclusive bounds for Integer/Number
  std::optional<double> max{};
  bool exclusive_min = false;          // true: value must be > min
  std::vector<std::string> choices{};  // allowed values for String
  IntegerKind integer_kind = IntegerKind::int32;  // Integer: the type the value is read into
};

// Convenience constructors, so schemas read as tables.
ParamSpec number_param(std::string name, json def, std::string description, std::optional<double> min = {},
                       std::optional<double> max = {}, bool exclusive_min = false);
ParamSpec integer_param(std::string name, json def, std::string description, std::optional<double> min = {},
                        std::optional<double> max = {}, IntegerKind kind = IntegerKind::int32);
ParamSpec string_param(std::string name, json def, std::string description, std::vector<std::string> choices = {});
ParamSpec bool_param(std::string name, bool def, std::string description);
ParamSpec object_param(std::string name, json def, std::string description);
ParamSpec array_param(std::string name, json def, std::string description);
ParamSpec entry_param(std::string name, json def, std::string description);

using ParamSchema = std::vector<ParamSpec>;

// Validates `given` (an object, or null for "all defaults") against `schema` and returns the object with
// defaults filled in. `path` is the JSON pointer of `given`, used in error messages. Keys listed in
// `passthrough` are accepted without checking (e.g. "name").
json resolve_params(const json& given, const ParamSchema& schema, const std::string& path,
                    const std::vector<std::string>& passthrough = {"name"});

std::string to_string(ParamType t);
json schema_to_json(const ParamSchema& schema);

// Reads and parses a JSON file; a clear ConfigError on a missing file, a syntax error, a file that is not a
// regular file or too large, nesting deeper than 64 levels or a duplicate key (core/base/json_reader.hpp).
json read_json_file(const std::string& file);

// Throws NumericalError naming `what` if `x` is not finite.
double require_finite(double x, const std::string& what);

}  // namespace closurelab
