#pragma once
// The command line's options, declared once: each command (run, deconvolve, export, store, merge, list) is one
// CommandSpec, a table of its positional arguments and options, each with its value's name and its meaning.
// The usage text (`closurelab COMMAND --help`, and the synopsis in `closurelab --help`), the parser, and every
// message about a bad invocation (an unknown option and the valid ones, a missing or empty value, a value of the
// wrong form, a missing required option or argument, one argument too many) are generated from that one table,
// so they cannot disagree. A bad invocation is a UsageError: exit 2, the message, then the command's synopsis.
//
//   const CommandSpec spec{"store", {}, "Lists the reference store.", {store_option()}, ""};
//   const ParsedArgs args = parse_command_line(spec, argc, argv);   // throws UsageError
//   const std::string dir = args.value("--store", default_dir);
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/base/errors.hpp"

namespace closurelab {

// A value's form, checked by the parser (the message names the option, the form and the value given).
enum class ValueForm {
  text,              // any non-empty text
  positive_integer,  // 1, 2, ... (decimal digits only)
  number_nonneg,     // a finite decimal number >= 0 (no hexadecimal, inf or nan)
  key_value,         // KEY=VALUE with a non-empty KEY
};

struct OptionSpec {
  std::string name;         // "--out"
  std::string value;        // the value's name in the usage ("DIR"); empty: a flag without a value
  std::string help = {};    // its meaning; may hold '\n' for a second line
  bool repeatable = false;  // may be given more than once (every value kept, in order)
  bool required = false;
  ValueForm form = ValueForm::text;
  // A further check of the value (e.g. parse_shard): throws a ConfigError naming the option.
  std::function<void(const std::string&)> check = {};
};

struct PositionalSpec {
  std::string name;  // "SPEC.json"
  bool required = true;
};

struct CommandSpec {
  std::string name;                        // "run"
  std::vector<PositionalSpec> positionals;  // in order; at most one value each
  std::string description;                 // what the command does (the usage's paragraph)
  std::vector<OptionSpec> options;         // --help is implied: every command has it
  std::string epilogue = {};                  // after the options (exit codes, notes)
  std::vector<std::string> more_synopses = {};  // further synopsis lines (e.g. under mpirun)
};

// A bad invocation: the message, and the synopsis of the command it concerns (printed after it, exit 2).
class UsageError : public ConfigError {
 public:
  UsageError(const CommandSpec& spec, const std::string& message);
  const std::string& usage_lines() const { return usage_lines_; }  // "usage: closurelab run ...\n"

 private:
  std::string usage_lines_;
};

struct ParsedArgs {
  std::vector<std::string> positionals;
  std::map<std::string, std::vector<std::string>> values;  // an option given: its values (a flag: one "")

  bool has(const std::string& option) const { return values.count(option) > 0; }
  // The (last) value of `option`, or `fallback` when it was not given.
  std::string value(const std::string& option, const std::string& fallback = "") const;
  std::vector<std::string> all(const std::string& option) const;
  std::string positional(std::size_t i, const std::string& fallback = "") const;
};

// "closurelab run SPEC.json [--out DIR] [--jobs N] ...", wrapped to `width` columns (continuations indented).
std::string synopsis(const CommandSpec& spec, std::size_t width = 112);
// The synopsis after "usage: ", its further lines indented to match.
std::string usage_lines(const CommandSpec& spec);
// The full usage: usage_lines, the description, every option with its meaning, the epilogue.
std::string usage(const CommandSpec& spec);

// Whether --help or -h stands anywhere after the command (not as another option's value): it wins.
bool wants_help(const CommandSpec& spec, int argc, char** argv);

// Parses argv[2..argc) against `spec`; throws UsageError on anything the table does not allow.
ParsedArgs parse_command_line(const CommandSpec& spec, int argc, char** argv);

// Shared by run and store: the reference store's folder.
OptionSpec store_option();

}  // namespace closurelab
