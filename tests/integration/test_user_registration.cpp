// The registration hook (experiments/runner/closurelab_main.hpp): a user's executable calls closurelab_main with
// its own entries, and list, run and deconvolve see them; a name registered twice is an error (exit 1).
#include <gtest/gtest.h>

#include <iostream>
#include <sstream>

#include "tests/support/cli_run.hpp"
#include "core/closure/deconvolver.hpp"
#include "experiments/kinds/experiment_kind.hpp"
#include "experiments/runner/closurelab_main.hpp"

using namespace closurelab;

namespace {

struct Captured {
  int rc;
  std::string out, err;
};

Captured run_main(std::vector<std::string> args, const UserRegistration& hook) {
  args.insert(args.begin(), "custom_closurelab");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  std::stringstream out, err;
  auto* old_out = std::cout.rdbuf(out.rdbuf());
  auto* old_err = std::cerr.rdbuf(err.rdbuf());
  const int rc = closurelab_main(static_cast<int>(argv.size()), argv.data(), hook);
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  return {rc, out.str(), err.str()};
}

// A user's deconvolver: CGLS under another name (the factory of a built-in, reached through the registry).
void register_my_cgls(Registry& r) {
  EntryInfo info = r.deconvolvers.info("cgls");
  info.name = "my_cgls";
  info.description = "a user's entry (cgls under another name)";
  r.deconvolvers.add(info, [&r](const json& p) {
    json q = p;
    q["name"] = "cgls";
    return r.deconvolvers.create(q, "");
  });
}

}  // namespace

TEST(UserRegistration, ListShowsTheUsersEntryBesideTheBuiltins) {
  const Captured c = run_main({"list", "deconvolver"}, register_my_cgls);
  EXPECT_EQ(c.rc, 0) << c.err;
  EXPECT_NE(c.out.find("my_cgls - a user's entry"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("tikhonov - "), std::string::npos) << c.out;
  const Captured stock = run_main({"list", "deconvolver"}, {});
  EXPECT_EQ(stock.out.find("my_cgls"), std::string::npos) << "the stock program has no user entries";
}

TEST(UserRegistration, ASpecRunsTheUsersEntry) {
  const auto work = closurelab::testing::fresh_work_folder("user_registration");
  closurelab::testing::write_text(work / "spec.json", R"({
    "name": "user_entry", "kind": "deconvolution_stability",
    "base": {"problem": {"name": "gaussian_averaging", "coarse_count": 16}, "noise": 0.01, "scan_best": false},
    "cells": [{"method": {"name": "my_cgls", "rule": "discrepancy"}}]})");
  const Captured c = run_main({"run", (work / "spec.json").string(), "--out", (work / "out").string()}, register_my_cgls);
  EXPECT_EQ(c.rc, 0) << c.err;
  const json table = json::parse(closurelab::testing::read_text(work / "out" / "user_entry.json"));
  ASSERT_EQ(table.at("rows").size(), 1u);
  EXPECT_NE(table["rows"][0].value("status", ""), "error") << table["rows"][0].dump();
  EXPECT_EQ(table["rows"][0]["params"]["method"]["name"], "my_cgls");
  // The stock program does not know it: an error naming the JSON path, exit 2.
  const Captured stock = run_main({"run", (work / "spec.json").string(), "--out", (work / "out2").string()}, {});
  EXPECT_EQ(stock.rc, 2);
  EXPECT_NE(stock.err.find("/method"), std::string::npos) << stock.err;
  EXPECT_NE(stock.err.find("unknown deconvolver 'my_cgls'"), std::string::npos) << stock.err;
}

TEST(UserRegistration, ANameRegisteredTwiceIsAnError) {
  const Captured c = run_main({"list"}, [](Registry& r) { r.deconvolvers.add(r.deconvolvers.info("cgls"), nullptr); });
  EXPECT_EQ(c.rc, 1);
  EXPECT_NE(c.err.find("deconvolver 'cgls' is registered twice"), std::string::npos) << c.err;
  EXPECT_EQ(c.err.back(), '\n');
}

namespace {

// A user's experiment kind: one section with one parameter, a row that echoes it.
class EchoKind : public ExperimentKind {
 public:
  std::string name() const override { return "my_echo"; }
  std::string description() const override { return "a user's experiment kind (echoes its value)"; }
  std::vector<KindSection> sections() const override {
    return {{"echo", "what to echo", "", {number_param("value", 1.0, "the value echoed into errors.value")}}};
  }
  json resolve(const json& cell, const std::string& path, const Registry&) const override {
    for (const auto& [k, v] : cell.items())
      if (k != "echo") throw ConfigError(path + "/" + k, "unknown key; allowed: echo");
    return {{"echo", resolve_params(cell.value("echo", json::object()), sections()[0].params, path + "/echo", {})}};
  }
  json run(const json& cfg, const Registry&, const ProgressFn&) const override {
    return {{"status", "ok"}, {"errors", {{"value", cfg.at("echo").at("value")}}}, {"cost", json::object()}};
  }
};

void register_echo(Registry& r) { r.experiments.add(std::make_unique<EchoKind>()); }

}  // namespace

TEST(UserRegistration, AUsersExperimentKindIsListedAndRuns) {
  const Captured list = run_main({"list", "experiment"}, register_echo);
  EXPECT_EQ(list.rc, 0) << list.err;
  EXPECT_NE(list.out.find("my_echo - a user's experiment kind"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("reduced_model - "), std::string::npos) << list.out;
  const auto work = closurelab::testing::fresh_work_folder("user_kind");
  closurelab::testing::write_text(work / "spec.json", R"({"name": "echo", "kind": "my_echo",
    "base": {}, "axes": {"echo.value": [2.5, 4.0]}})");
  const Captured c = run_main({"run", (work / "spec.json").string(), "--out", (work / "out").string()}, register_echo);
  EXPECT_EQ(c.rc, 0) << c.err;
  const json table = json::parse(closurelab::testing::read_text(work / "out" / "echo.json"));
  ASSERT_EQ(table.at("rows").size(), 2u);
  EXPECT_EQ(table["rows"][1]["errors"]["value"], 4.0);
  // Without the hook the kind is unknown (exit 2, the known kinds named); a built-in's name is refused (exit 1).
  const Captured stock = run_main({"run", (work / "spec.json").string(), "--out", (work / "out2").string()}, {});
  EXPECT_EQ(stock.rc, 2);
  EXPECT_NE(stock.err.find("unknown experiment kind 'my_echo'"), std::string::npos) << stock.err;
  struct Clash : EchoKind {
    std::string name() const override { return "reduced_model"; }
  };
  const Captured twice = run_main({"list"}, [](Registry& r) { r.experiments.add(std::make_unique<Clash>()); });
  EXPECT_EQ(twice.rc, 1);
  EXPECT_NE(twice.err.find("experiment kind 'reduced_model' is registered twice"), std::string::npos) << twice.err;
}
