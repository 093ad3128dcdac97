// Experiment kind "deconvolution_stability": a test problem (Gaussian averaging at one of the three
// discretizations of §4.2, the cut-off Gaussian, or the classic shaw / deriv2 / phillips problems), a relative
// noise level with a recorded seed, and a deconvolver with its parameter rule. The row reports the rule's error,
// the best error over the method's regularized family and their ratio, κ(A), finiteness, status and cost
// (experiments/testproblems/stability_case.hpp does the work; the gtests use the same function).
//
// Cell: {"problem": {"name": ..., ...}, "method": {"name": ..., "rule": ...}, "noise": 0.01, "seed": 12345,
//        "scan_best": true}
#include "experiments/kinds/stability_experiment.hpp"

#include <algorithm>

#include "core/base/errors.hpp"
#include "experiments/testproblems/ill_posed_problems.hpp"
#include "experiments/testproblems/stability_case.hpp"
#include "core/closure/deconvolver.hpp"

namespace closurelab {
namespace {

const std::vector<std::string> problem_names = {"gaussian_averaging", "shaw", "deriv2", "phillips"};

ParamSchema run_schema() {
  return {number_param("noise", 0.0, "relative noise ||e||/||b||", 0.0, 10.0),
          integer_param("seed", 12345, "noise RNG seed (std::mt19937_64)", 0, {}, IntegerKind::uint64),
          bool_param("scan_best", true, "scan the family for the best parameter")};
}

class StabilityExperiment : public ExperimentKind {
 public:
  std::string name() const override { return "deconvolution_stability"; }
  std::string description() const override {
    return "deconvolution hard cases: rule error vs best scanned parameter, kappa(A), finiteness, cost";
  }

  std::vector<KindSection> sections() const override {
    return {{"problem", "the test problem (required): name one of gaussian_averaging, shaw, deriv2, phillips", "",
             ill_posed_problem_schema()},
            {"method", "the deconvolver (required)", "deconvolver", {}},
            {"noise, seed, scan_best", "top-level keys of the cell", "", run_schema()}};
  }

  json resolve(const json& cell, const std::string& path, const Registry& reg) const override {
    if (!cell.is_object()) throw ConfigError(path, "expected an object");
    for (const auto& [k, v] : cell.items())
      if (k != "problem" && k != "method" && k != "noise" && k != "seed" && k != "scan_best")
        throw ConfigError(path + "/" + k, "unknown key; allowed keys: problem, method, noise, seed, scan_best");
    if (!cell.contains("problem")) throw ConfigError(path + "/problem", "missing problem");
    if (!cell.contains("method")) throw ConfigError(path + "/method", "missing method (a deconvolver)");
    const json& pr = cell.at("problem");
    if (!pr.is_object() || !pr.contains("name") || !pr.at("name").is_string())
      throw ConfigError(path + "/problem/name", "missing string name; known: gaussian_averaging, shaw, deriv2, phillips");
    const std::string pname = pr.at("name").get<std::string>();
    if (std::find(problem_names.begin(), problem_names.end(), pname) == problem_names.end())
      throw ConfigError(path + "/problem/name", "unknown problem '" + pname + "'; known: gaussian_averaging, shaw, deriv2, phillips");
    json out;
    out["problem"] = resolve_params(pr, ill_posed_problem_schema(), path + "/problem");
    out["problem"]["name"] = pname;
    if (pname == "gaussian_averaging") check_ill_posed_problem_size(out["problem"], path + "/problem");
    // create, not only resolve: the factory's cross-parameter checks (alpha_min < alpha_max) are validation.
    reg.deconvolvers.create(cell.at("method"), path + "/method", &out["method"]);
    const json rest = resolve_params(json{{"noise", cell.value("noise", json(0.0))},
                                          {"seed", cell.value("seed", json(12345))},
                                          {"scan_best", cell.value("scan_best", json(true))}},
                                     run_schema(), path);
    out["noise"] = rest["noise"];
    out["seed"] = rest["seed"];
    out["scan_best"] = rest["scan_best"];
    return out;
  }

  json run(const json& r, const Registry& reg, const ProgressFn&) const override {
    const IllPosedProblem p = make_ill_posed_problem(r.at("problem"), "/problem");
    StabilityCaseInput in;
    in.noise = r.at("noise").get<double>();
    in.seed = r.at("seed").get<std::uint64_t>();
    in.method = r.at("method");
    in.scan_best = r.at("scan_best").get<bool>();
    return run_stability_case(p, in, reg);
  }
};

}  // namespace

std::unique_ptr<ExperimentKind> make_stability_experiment() { return std::make_unique<StabilityExperiment>(); }

}  // namespace closurelab
