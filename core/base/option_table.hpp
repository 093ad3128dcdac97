#pragma once
// An options struct's section of a spec, declared once: each option names its member, its JSON name, its doc and
// its range or choices, and its default is the struct's own (`O{}`). From that one declaration come the section's
// schema (validation, defaults, `closurelab list`, docs/parameters.md) and its reader (resolved JSON -> O), so an
// option is written twice (the struct's member with its default, one line here) instead of three times (member,
// schema entry, reader line). deal.II's ParameterHandler::add_parameter and Ginkgo's factory parameters bind a
// variable to its declaration the same way.
//
//   const OptionTable<MyOptions>& my_options() {
//     static const OptionTable<MyOptions> table = OptionTable<MyOptions>("/solver")
//         .number("kappa", &MyOptions::kappa, "time-step coefficient", 0.0, 1.0, true)
//         .choice("scheme", &MyOptions::scheme, "paper or staggered")
//         .time_loop();
//     return table;
//   }
//   my_options().schema();              // ParamSchema, in declaration order
//   my_options().read(resolved_solver); // MyOptions
#include <cstdint>
#include <functional>
#include <type_traits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/base/enum_names.hpp"
#include "core/base/params.hpp"
#include "core/base/time_loop.hpp"

namespace closurelab {

template <class O>
class OptionTable {
 public:
  using Reader = std::function<void(const json& resolved, O& options)>;
  using Check = std::function<void(const O& options)>;

  // `section`: the section's JSON path ("/solver"), for the messages of a reader.
  explicit OptionTable(std::string section) : section_(std::move(section)) {}

  // `member`: a pointer to O's member, or a callable giving a reference to it from an O& (a nested member:
  // [](O& o) -> double& { return o.engine.factor; }).
  template <class M>
  OptionTable&& number(std::string name, M member, std::string doc, std::optional<double> min = {},
                       std::optional<double> max = {}, bool exclusive_min = false) && {
    specs_.push_back(number_param(name, field(member, defaults_), std::move(doc), min, max, exclusive_min));
    readers_.push_back([name, member](const json& s, O& o) { field(member, o) = s.at(name).template get<double>(); });
    return std::move(*this);
  }
  template <class M>
  OptionTable&& integer(std::string name, M member, std::string doc, std::optional<double> min = {},
                        std::optional<double> max = {}) && {
    specs_.push_back(integer_param(name, field(member, defaults_), std::move(doc), min, max));
    readers_.push_back([name, member](const json& s, O& o) { field(member, o) = s.at(name).template get<int>(); });
    return std::move(*this);
  }
  template <class M>
  OptionTable&& boolean(std::string name, M member, std::string doc) && {
    specs_.push_back(bool_param(name, field(member, defaults_), std::move(doc)));
    readers_.push_back([name, member](const json& s, O& o) { field(member, o) = s.at(name).template get<bool>(); });
    return std::move(*this);
  }
  // An enumeration, by its name table (core/base/enum_names.hpp): the choices are its names, in table order.
  template <class M>
  OptionTable&& choice(std::string name, M member, std::string doc) && {
    using E = std::remove_cvref_t<std::invoke_result_t<M, O&>>;
    specs_.push_back(string_param(name, name_of(field(member, defaults_)), std::move(doc), names_of<E>()));
    readers_.push_back([name, member, path = section_ + "/" + name](const json& s, O& o) {
      field(member, o) = parse_name<E>(s.at(name).template get<std::string>(), path);
    });
    return std::move(*this);
  }
  // An entry of the section that the struct does not hold (read from the JSON by its user, e.g. an integrator
  // named by the section and created from the registry).
  OptionTable&& unbound(ParamSpec spec) && {
    specs_.push_back(std::move(spec));
    return std::move(*this);
  }
  // The run-control parameters of TimeLoopOptions (core/base/time_loop.hpp), with O's defaults.
  OptionTable&& time_loop() && {
    for (auto& p : time_loop_schema(defaults_)) specs_.push_back(std::move(p));
    readers_.push_back([](const json& s, O& o) { read_time_loop(s, o); });
    return std::move(*this);
  }
  // A check of the read options beyond one option's range (a ConfigError naming the option).
  OptionTable&& check(Check c) && {
    checks_.push_back(std::move(c));
    return std::move(*this);
  }

  const std::string& section() const { return section_; }
  ParamSchema schema() const { return specs_; }
  // The options of a section resolved against schema() (every option present).
  O read(const json& resolved) const {
    O o;
    read_into(resolved, o);
    return o;
  }
  // The same into `o`, whose other members stay (a section that fills part of a struct another section fills too).
  void read_into(const json& resolved, O& o) const {
    for (const Reader& r : readers_) r(resolved, o);
    for (const Check& c : checks_) c(o);
  }

 private:
  template <class M>
  static decltype(auto) field(const M& member, O& o) {
    return std::invoke(member, o);
  }

  std::string section_;
  O defaults_{};
  ParamSchema specs_;
  std::vector<Reader> readers_;
  std::vector<Check> checks_;
};

}  // namespace closurelab
