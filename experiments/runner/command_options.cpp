#include "experiments/runner/command_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace closurelab {

namespace {

// "--out DIR", "--force", "--param k=v ..." as the synopsis shows them.
std::string option_words(const OptionSpec& o) {
  std::string s = o.name;
  if (!o.value.empty()) s += " " + o.value;
  if (o.repeatable) s += " ...";
  return s;
}

std::vector<std::string> synopsis_words(const CommandSpec& spec) {
  std::vector<std::string> words = {"closurelab", spec.name};
  // (appended piecewise: "[" + s + "]" trips a false -Wrestrict of GCC 12)
  auto bracketed = [](const std::string& s, bool required) {
    std::string w = required ? "" : "[";
    w.append(s);
    if (!required) w.push_back(']');
    return w;
  };
  for (const PositionalSpec& p : spec.positionals) words.push_back(bracketed(p.name, p.required));
  for (const OptionSpec& o : spec.options) words.push_back(bracketed(option_words(o), o.required));
  return words;
}

std::string valid_options(const CommandSpec& spec) {
  std::string s;
  for (const OptionSpec& o : spec.options) s += o.name + ", ";
  return s + "--help";
}

const OptionSpec* find_option(const CommandSpec& spec, const std::string& name) {
  for (const OptionSpec& o : spec.options)
    if (o.name == name) return &o;
  return nullptr;
}

bool is_help(const char* a) { return std::strcmp(a, "--help") == 0 || std::strcmp(a, "-h") == 0; }

// The form's check: an empty string when `v` has it, else what was expected.
std::string form_problem(ValueForm form, const std::string& v) {
  switch (form) {
    case ValueForm::text:
      return v.empty() ? "a non-empty value" : "";
    case ValueForm::positive_integer: {
      const bool digits = !v.empty() && v.size() <= 9 && v.find_first_not_of("0123456789") == std::string::npos;
      return digits && std::atoi(v.c_str()) >= 1 ? "" : "a positive integer";
    }
    case ValueForm::number_nonneg: {
      // strtod also reads hexadecimal ("0x10" = 16) and "inf"/"nan": a decimal number only.
      const bool decimal = !v.empty() && v.find_first_not_of("0123456789.eE+-") == std::string::npos;
      char* end = nullptr;
      const double x = decimal ? std::strtod(v.c_str(), &end) : -1.0;
      return decimal && end != v.c_str() && *end == '\0' && std::isfinite(x) && x >= 0 ? "" : "a finite number >= 0";
    }
    case ValueForm::key_value: {
      const auto eq = v.find('=');
      return eq == std::string::npos || eq == 0 ? "a non-empty KEY before '='" : "";
    }
  }
  return "";
}

}  // namespace

UsageError::UsageError(const CommandSpec& spec, const std::string& message)
    : ConfigError("", message), usage_lines_(closurelab::usage_lines(spec)) {}

std::string ParsedArgs::value(const std::string& option, const std::string& fallback) const {
  const auto it = values.find(option);
  return it == values.end() || it->second.empty() ? fallback : it->second.back();
}

std::vector<std::string> ParsedArgs::all(const std::string& option) const {
  const auto it = values.find(option);
  return it == values.end() ? std::vector<std::string>{} : it->second;
}

std::string ParsedArgs::positional(std::size_t i, const std::string& fallback) const {
  return i < positionals.size() ? positionals[i] : fallback;
}

std::string synopsis(const CommandSpec& spec, std::size_t width) {
  const std::vector<std::string> words = synopsis_words(spec);
  const std::string indent(std::strlen("closurelab ") + spec.name.size() + 1, ' ');
  std::string out, line;
  for (const std::string& w : words) {
    if (!line.empty() && line.size() + 1 + w.size() > width) {
      out += line + "\n";
      line = indent;
    }
    line += (line.empty() || line == indent ? "" : " ") + w;
  }
  out += line + "\n";
  for (const std::string& s : spec.more_synopses) out += s + "\n";
  return out;
}

std::string usage_lines(const CommandSpec& spec) {
  std::ostringstream os;
  std::istringstream lines(synopsis(spec));
  std::string l;
  for (bool first = true; std::getline(lines, l); first = false) os << (first ? "usage: " : "       ") << l << "\n";
  return os.str();
}

std::string usage(const CommandSpec& spec) {
  std::ostringstream os;
  os << usage_lines(spec);
  if (!spec.description.empty()) os << spec.description << "\n";
  std::size_t col = std::strlen("--help");
  for (const OptionSpec& o : spec.options) col = std::max(col, option_words(o).size());
  col = std::min<std::size_t>(col + 4, 24);
  auto item = [&](const std::string& words, const std::string& help) {
    os << "  " << words;
    if (words.size() + 2 >= col + 2) os << "\n" << std::string(col + 2, ' ');
    else os << std::string(col - words.size(), ' ');
    for (char c : help) os << c << (c == '\n' ? std::string(col + 2, ' ') : "");
    os << "\n";
  };
  for (const OptionSpec& o : spec.options) item(option_words(o), o.help + (o.required ? " (required)" : ""));
  item("--help", "this text");
  if (!spec.epilogue.empty()) os << spec.epilogue << (spec.epilogue.back() == '\n' ? "" : "\n");
  return os.str();
}

bool wants_help(const CommandSpec& spec, int argc, char** argv) {
  (void)spec;  // --help wins wherever it stands, even where another option expects a value
  for (int i = 2; i < argc; ++i)
    if (is_help(argv[i])) return true;
  return false;
}

ParsedArgs parse_command_line(const CommandSpec& spec, int argc, char** argv) {
  ParsedArgs args;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.empty() || a[0] != '-') {
      if (args.positionals.size() >= spec.positionals.size()) {
        const std::size_t n = spec.positionals.size();
        const std::string what = n == 0 ? "no arguments"
                                 : n == 1 ? (spec.positionals[0].required ? "one " : "at most one ") + spec.positionals[0].name
                                          : "at most " + std::to_string(n) + " arguments";
        throw UsageError(spec, spec.name + " takes " + what + "; '" + a + "' is one argument too many");
      }
      args.positionals.push_back(a);
      continue;
    }
    const OptionSpec* o = find_option(spec, a);
    if (!o) throw UsageError(spec, "unknown option '" + a + "'; valid: " + valid_options(spec));
    if (o->value.empty()) {
      args.values[a] = {""};
      continue;
    }
    if (i + 1 >= argc) throw UsageError(spec, a + ": missing value (" + option_words(*o) + ")");
    const std::string v = argv[++i];
    if (const std::string want = form_problem(o->form, v); !want.empty())
      throw UsageError(spec, a + " needs " + o->value + " (" + want + "), got '" + v + "'");
    if (o->check) {
      try {
        o->check(v);
      } catch (const ConfigError& e) {
        throw UsageError(spec, e.what());
      }
    }
    auto& vs = args.values[a];
    if (!o->repeatable) vs.clear();  // given twice: the last holds
    vs.push_back(v);
  }
  for (std::size_t k = args.positionals.size(); k < spec.positionals.size(); ++k)
    if (spec.positionals[k].required) throw UsageError(spec, spec.name + " needs " + spec.positionals[k].name);
  for (const OptionSpec& o : spec.options)
    if (o.required && !args.has(o.name))
      throw UsageError(spec, o.name + (o.value.empty() ? "" : " " + o.value) + " is required: " + o.help);
  return args;
}

OptionSpec store_option() {
  return {"--store", "DIR",
          "the reference store: direct SPH runs kept across cells, specs, runs and ranks\n"
          "(default $CLOSURELAB_STORE, else ~/.cache/closurelab/store); `closurelab store` lists it"};
}

}  // namespace closurelab
