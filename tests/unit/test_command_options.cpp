// The command line's options are declared once (experiments/runner/command_options.hpp): every option of every
// command's table appears in its usage and synopsis and in the "valid:" list of an unknown option, and the
// parser takes exactly what the table declares (values, flags, repeats, forms, required options, positionals).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/base/registry.hpp"
#include "experiments/runner/command_options.hpp"
#include "experiments/runner/deconvolve_command.hpp"
#include "experiments/runner/export_command.hpp"
#include "experiments/runner/run_command.hpp"
#include "experiments/runner/seal_command.hpp"

using namespace closurelab;

namespace {

// argv for parse_command_line: "closurelab CMD args..."
struct Argv {
  std::vector<std::string> words;
  std::vector<char*> ptrs;
  explicit Argv(std::vector<std::string> w) : words(std::move(w)) {
    for (auto& s : words) ptrs.push_back(s.data());
  }
  int argc() const { return static_cast<int>(ptrs.size()); }
  char** argv() { return ptrs.data(); }
};

std::string usage_error(const CommandSpec& spec, std::vector<std::string> args) {
  args.insert(args.begin(), {"closurelab", spec.name});
  Argv a(args);
  try {
    parse_command_line(spec, a.argc(), a.argv());
  } catch (const UsageError& e) {
    EXPECT_EQ(e.usage_lines().rfind("usage: closurelab " + spec.name, 0), 0u) << e.usage_lines();
    return e.what();
  }
  return "";
}

std::vector<CommandSpec> every_command() {
  static Registry registry = [] {
    Registry r;
    register_builtin_strategies(r);
    return r;
  }();
  return {run_command_spec(), deconvolve_command_spec(registry), export_command_spec(), seal_command_spec()};
}

}  // namespace

TEST(CommandOptions, EveryDeclaredOptionIsInTheUsageTheSynopsisAndTheValidList) {
  for (const CommandSpec& spec : every_command()) {
    const std::string text = usage(spec), syn = synopsis(spec), unknown = usage_error(spec, {"--frob"});
    EXPECT_EQ(text.rfind("usage: closurelab " + spec.name, 0), 0u) << text;
    EXPECT_NE(unknown.find("'--frob'"), std::string::npos) << unknown;
    for (const OptionSpec& o : spec.options) {
      EXPECT_NE(text.find("  " + o.name), std::string::npos) << spec.name << " usage lacks " << o.name;
      EXPECT_NE(syn.find(o.name + (o.value.empty() ? "" : " " + o.value)), std::string::npos) << o.name;
      EXPECT_NE(unknown.find(o.name + ","), std::string::npos) << unknown;
      EXPECT_FALSE(o.help.empty()) << spec.name << " " << o.name;
    }
    EXPECT_NE(text.find("--help"), std::string::npos);
    for (const PositionalSpec& p : spec.positionals) EXPECT_NE(syn.find(p.name), std::string::npos);
  }
}

TEST(CommandOptions, ParsesValuesFlagsRepeatsAndPositionals) {
  const CommandSpec& run = run_command_spec();
  Argv a({"closurelab", "run", "s.json", "--set", "a.b=1", "--force", "--out", "o1", "--set", "c=x", "--out", "o2"});
  const ParsedArgs p = parse_command_line(run, a.argc(), a.argv());
  EXPECT_EQ(p.positional(0), "s.json");
  EXPECT_TRUE(p.has("--force"));
  EXPECT_FALSE(p.has("--dry-run"));
  EXPECT_EQ(p.value("--out"), "o2");  // given twice: the last holds
  EXPECT_EQ(p.all("--set"), (std::vector<std::string>{"a.b=1", "c=x"}));
  EXPECT_EQ(p.value("--store", "fallback"), "fallback");
}

TEST(CommandOptions, BadInvocationsNameTheProblem) {
  const CommandSpec& run = run_command_spec();
  EXPECT_NE(usage_error(run, {}).find("SPEC.json"), std::string::npos);
  EXPECT_NE(usage_error(run, {"a", "b"}).find("'b'"), std::string::npos);
  EXPECT_NE(usage_error(run, {"s", "--out"}).find("--out: missing value"), std::string::npos);
  EXPECT_NE(usage_error(run, {"s", "--out", ""}).find("--out needs DIR"), std::string::npos);
  EXPECT_NE(usage_error(run, {"s", "--jobs", "0"}).find("positive integer"), std::string::npos);
  EXPECT_NE(usage_error(run, {"s", "--jobs", "+3"}).find("'+3'"), std::string::npos);
  EXPECT_NE(usage_error(run, {"s", "--set", "=1"}).find("KEY"), std::string::npos);
  EXPECT_NE(usage_error(run, {"s", "--shard", "4/4"}).find("below the count"), std::string::npos);
  EXPECT_EQ(usage_error(run, {"s", "--jobs", "3", "--shard", "0/2", "--set", "k=v"}), "");
  const CommandSpec dec = every_command()[1];
  EXPECT_NE(usage_error(dec, {"--rhs", "b"}).find("--matrix A.mtx is required"), std::string::npos);
  EXPECT_NE(usage_error(dec, {"--matrix", "a", "--rhs", "b"}).find("--method NAME is required"), std::string::npos);
  EXPECT_NE(usage_error(dec, {"--matrix", "a", "--rhs", "b", "--method", "cg", "--noise-level", "inf"}).find("'inf'"),
            std::string::npos);
}

TEST(CommandOptions, HelpWinsWhereverItStands) {
  const CommandSpec& run = run_command_spec();
  Argv a({"closurelab", "run", "--frob", "--out", "-h"});
  EXPECT_TRUE(wants_help(run, a.argc(), a.argv()));
  Argv b({"closurelab", "run", "s.json"});
  EXPECT_FALSE(wants_help(run, b.argc(), b.argv()));
}
