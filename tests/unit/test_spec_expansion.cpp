// Spec semantics (experiments/runner/runner.hpp): a cell's object merges into the base's (deep merge) unless it
// names another strategy; `--set KEY=VALUE` holds in every cell, over the base, the axes and the cells.
#include <gtest/gtest.h>

#include "core/base/errors.hpp"
#include "experiments/runner/runner.hpp"

using namespace closurelab;

namespace {

json spec_with(json cells, json axes = nullptr) {
  json s = {{"name", "t"},
            {"kind", "reduced_model"},
            {"base",
             {{"solver", {{"scheme", "paper"}, {"kappa", 0.25}, {"balance", "force_density"}}},
              {"closure", {{"deconvolver", {{"name", "tikhonov"}, {"alpha", 1e-6}}}}}}}};
  if (!cells.is_null()) s["cells"] = cells;
  if (!axes.is_null()) s["axes"] = axes;
  return s;
}

}  // namespace

TEST(SpecExpansion, ACellObjectKeepsTheBaseKeysItDoesNotName) {
  const auto cells = expand_matrix(spec_with(json::array({{{"label", "staggered"}, {"solver", {{"scheme", "staggered"}}}}})));
  ASSERT_EQ(cells.size(), 1u);
  const json& solver = cells[0].config.at("solver");
  EXPECT_EQ(solver.at("scheme"), "staggered");
  EXPECT_EQ(solver.at("kappa"), 0.25);
  EXPECT_EQ(solver.at("balance"), "force_density");
}

TEST(SpecExpansion, AnObjectNamingAnotherStrategyReplacesTheBaseOne) {
  const auto cells = expand_matrix(spec_with(json::array(
      {{{"closure", {{"deconvolver", {{"name", "truncated_svd"}, {"k", 3}}}}}},
       {{"closure", {{"deconvolver", {{"name", "tikhonov"}, {"rule", "gcv"}}}}}}})));
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].config.at("closure").at("deconvolver"), (json{{"name", "truncated_svd"}, {"k", 3}}));
  // The same strategy: its parameters merge.
  EXPECT_EQ(cells[1].config.at("closure").at("deconvolver"),
            (json{{"name", "tikhonov"}, {"alpha", 1e-6}, {"rule", "gcv"}}));
}

TEST(SpecExpansion, SetHoldsInEveryCell) {
  json spec = spec_with(json::array({{{"solver", {{"kappa", 0.1}, {"max_time", 3.0}}}},
                                     {{"solver.kappa", 0.2}, {"solver.max_time", 4.0}},
                                     {{"label", "plain"}}}),
                        json{{"solver.scheme", json::array({"paper", "staggered"})}});
  // What the spec varied and --set replaces is said: the two cells' own kappa, the axis over the scheme.
  const std::vector<std::string> kappa = apply_override(spec, "solver.kappa=0.05");
  ASSERT_EQ(kappa.size(), 2u);
  EXPECT_EQ(kappa[0], "cell 0 gave solver.kappa = 0.1");
  EXPECT_EQ(kappa[1], "cell 1 gave solver.kappa = 0.2");
  const std::vector<std::string> scheme = apply_override(spec, "solver.scheme=staggered");  // not JSON: a string
  ASSERT_EQ(scheme.size(), 1u);
  EXPECT_EQ(scheme[0], "the axis solver.scheme over [\"paper\",\"staggered\"] is the one value \"staggered\" (the "
                       "matrix has 2 times fewer cells)");
  EXPECT_TRUE(apply_override(spec, "solver.scheme=staggered").empty());  // nothing left to replace
  const auto cells = expand_matrix(spec);
  ASSERT_EQ(cells.size(), 3u);  // the axis over solver.scheme keeps the one value
  for (const auto& c : cells) {
    EXPECT_EQ(c.config.at("solver").at("kappa"), 0.05) << c.label;
    EXPECT_EQ(c.config.at("solver").at("scheme"), "staggered") << c.label;
    EXPECT_EQ(c.config.at("solver").at("balance"), "force_density") << c.label;
  }
}

TEST(SpecExpansion, ANullOrAKeyGivenTwiceIsRefusedAtItsPath) {
  const auto path_of = [](const json& spec) {
    try {
      expand_matrix(spec);
    } catch (const ConfigError& e) {
      return e.path();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(path_of(spec_with(json::array({{{"solver", nullptr}}}))), "/cells/0/solver");
  EXPECT_EQ(path_of(spec_with(json::array({{{"solver", {{"kappa", nullptr}}}}}))), "/cells/0/solver/kappa");
  EXPECT_EQ(path_of(spec_with(nullptr, json{{"solver.kappa", json::array({0.1, nullptr})}})), "/axes/solver.kappa/1");
  EXPECT_EQ(path_of(spec_with(json::array({{{"solver", {{"kappa", 0.1}}}, {"solver.kappa", 0.2}}}))),
            "/cells/0/solver.kappa");
  EXPECT_EQ(path_of(spec_with(nullptr, json{{"solver", json::array({{{"kappa", 0.1}}, {{"scheme", "paper"}}})},
                                           {"solver.kappa", json::array({0.2, 0.3})}})),
            "/axes/solver.kappa");
  // Different keys of one object, dotted and inside it, are each given once.
  EXPECT_EQ(path_of(spec_with(json::array({{{"solver", {{"kappa", 0.1}}}, {"solver.scheme", "paper"}}}))), "accepted");
}

TEST(SpecExpansion, SetRefusesWhatItCannotHoldEverywhere) {
  json spec = spec_with(nullptr, json{{"solver.kappa", json::array({0.1, 0.2})}});
  EXPECT_THROW(apply_override(spec, "solver={\"scheme\": \"paper\"}"), ConfigError);  // the axis varies inside it
  EXPECT_THROW(apply_override(spec, "=3"), ConfigError);
  EXPECT_THROW(apply_override(spec, "solver.kappa"), ConfigError);
}
