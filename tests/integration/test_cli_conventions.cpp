// Command-line conventions: every command has --help (usage on stdout, exit 0); bad input names the bad
// flag or family and lists the valid ones, exit 2; every message ends with a newline; `list experiment`
// shows each kind's parameters like the other families.
#include <gtest/gtest.h>

#include <cctype>

#include "tests/support/cli_run.hpp"

using namespace closurelab::testing;

namespace {

bool ends_with_newline(const std::string& s) { return !s.empty() && s.back() == '\n'; }

}  // namespace

TEST(CliConventions, HelpOfEachCommandPrintsItsUsageAndExitsZero) {
  const auto work = fresh_work_folder("cli_help");
  for (const std::string cmd : {"run", "merge", "deconvolve", "list", "store", "export"}) {
    const CliOutcome o = run_closurelab(work, cmd + " --help");
    EXPECT_EQ(o.code, 0) << cmd << ": " << o.err;
    EXPECT_NE(o.out.find("usage: closurelab " + cmd), std::string::npos) << cmd << ": " << o.out;
    EXPECT_TRUE(ends_with_newline(o.out)) << cmd;
    EXPECT_TRUE(o.err.empty()) << cmd << ": " << o.err;
  }
  // --help wins wherever it stands, also after other (even bad) arguments.
  EXPECT_EQ(run_closurelab(work, "run spec.json --jobs 2 --help").code, 0);
  EXPECT_EQ(run_closurelab(work, "deconvolve --matrix A.mtx --help").code, 0);
  const CliOutcome top = run_closurelab(work, "--help");
  EXPECT_EQ(top.code, 0);
  EXPECT_NE(top.out.find("closurelab COMMAND --help"), std::string::npos);
}

struct BadInvocation {
  const char* args;
  std::vector<const char*> expected;  // fragments: the bad thing named, the valid ones listed
};

class CliBadInvocation : public ::testing::TestWithParam<BadInvocation> {};

TEST_P(CliBadInvocation, NamesTheProblemListsTheValidOnesExitTwoNewlineTerminated) {
  const auto work = fresh_work_folder("cli_bad");
  const BadInvocation& c = GetParam();
  const CliOutcome o = run_closurelab(work, c.args);
  EXPECT_EQ(o.code, 2) << c.args << ": " << o.err;
  EXPECT_TRUE(ends_with_newline(o.err)) << c.args << ": [" << o.err << "]";
  for (const char* f : c.expected) EXPECT_NE(o.err.find(f), std::string::npos) << c.args << ": " << o.err << " lacks " << f;
  // No message runs into the next one: every "error:" starts a line.
  for (std::size_t at = o.err.find("error:"); at != std::string::npos; at = o.err.find("error:", at + 1))
    EXPECT_TRUE(at == 0 || o.err[at - 1] == '\n') << c.args << ": [" << o.err << "]";
}

INSTANTIATE_TEST_SUITE_P(
    Invocations, CliBadInvocation,
    ::testing::Values(
        BadInvocation{"frobnicate", {"'frobnicate'", "list", "run", "merge", "deconvolve"}},
        BadInvocation{"list nonsense", {"'nonsense'", "kernel", "deconvolver", "quadrature", "scene", "experiment"}},
        BadInvocation{"list kernel extra", {"'extra'"}},
        BadInvocation{"run spec.json --frob",
                      {"'--frob'", "--out", "--jobs", "--force", "--store", "--shard", "--set", "--dry-run", "--help"}},
        BadInvocation{"run spec.json --store ''", {"--store"}},
        BadInvocation{"store --frob", {"'--frob'", "--store", "--help"}},
        BadInvocation{"run spec.json --shard 3", {"--shard", "i/N", "'3'"}},
        BadInvocation{"merge", {"DIR", "usage: closurelab merge"}},
        BadInvocation{"merge a b", {"DIR", "usage: closurelab merge"}},
        BadInvocation{"run spec.json --jobs 2x", {"--jobs", "'2x'"}},
        BadInvocation{"run spec.json --out ''", {"--out"}},
        BadInvocation{"run", {"SPEC.json"}},
        BadInvocation{"deconvolve --frob", {"--frob", "--matrix", "--rhs", "--method", "--help"}},
        BadInvocation{"deconvolve", {"--matrix", "usage: closurelab deconvolve"}},
        BadInvocation{"deconvolve --matrix", {"--matrix", "missing value"}},
        BadInvocation{"export --frob", {"'--frob'", "--csv", "--long", "--out", "--help"}},
        BadInvocation{"export", {"TABLE.json", "usage: closurelab export"}},
        BadInvocation{"run spec.json --set kappa", {"--set", "KEY=VALUE"}}),
    [](const ::testing::TestParamInfo<BadInvocation>& info) {
      std::string name = std::to_string(info.index) + "_";
      for (const char* c = info.param.args; *c; ++c) name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
      return name;
    });

TEST(CliConventions, ListExperimentShowsEachKindsParameters) {
  const auto work = fresh_work_folder("cli_list");
  const CliOutcome o = run_closurelab(work, "list experiment");
  ASSERT_EQ(o.code, 0) << o.err;
  for (const char* f : {"reduced_model", "direct_sph_validation", "deconvolution_stability", "quadrature_convergence",
                        // sections and their parameters, with types and defaults
                        "closure:", "discretization (string, default \"coarse_coarse\")", "steady_window (integer",
                        "t_over_tau (array", "averaging:", "mesh_spacing_over_eta (number", "problem:", "seed (integer",
                        "evaluation:", "repeats (integer",
                        // registered families are pointed to
                        "(parameters: closurelab list scene)", "(parameters: closurelab list deconvolver)"})
    EXPECT_NE(o.out.find(f), std::string::npos) << "missing '" << f << "' in:\n" << o.out;
  EXPECT_TRUE(ends_with_newline(o.out));
}
