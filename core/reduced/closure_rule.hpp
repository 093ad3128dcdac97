#pragma once
// The closure's parameter chosen once: the two-pass rule of the reduced models whose closure must be linear in its
// data. Backward Euler probes the rate's Jacobian once (core/reduced/integrator.hpp), and the force-density balance's
// steady state is one linear solve; a parameter rule (discrepancy, GCV, L-curve: core/closure/parameter_choice.hpp)
// applied at every solve moves its choice with the data, so its closure is not linear. Under such a model a
// deconvolver configured with a rule runs twice:
//   pass 1  the model to its end (the steady state) with the deconvolver at its configured fixed parameter;
//   choice  the rule applied once, to pass 1's data (the vector each closure deconvolves), picks the parameter;
//   pass 2  the model again with that parameter fixed: its result is the run's.
// A model with more than one closure (the force-density balance deconvolves the velocity and the density deviation)
// names each one a channel; each channel's parameter is chosen from its own data. Both passes and the choice are one
// reduced run: run_two_pass times them together (setup: the models' construction; loop: the runs and the choice).
#include <Eigen/Core>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "core/base/params.hpp"
#include "core/base/registry.hpp"
#include "core/base/repeated_timing.hpp"
#include "core/base/status.hpp"
#include "core/closure/deconvolver.hpp"

namespace closurelab {

class ForwardOperator;

// Which pass a model is built for (run_two_pass).
enum class ClosurePass { first, last };

class ClosureParameterRule {
 public:
  // Whether a deconvolver (resolved, closure.deconvolver) runs the two passes under a model: a rule other than fixed,
  // where the model needs a closure linear in its data.
  static bool applies(const json& resolved_deconvolver, bool model_needs_linear_closure);

  // `configured`: the resolved deconvolver; `noise_level`: δ handed to the rule (closure.noise_level).
  ClosureParameterRule(const Registry& registry, json configured, bool model_needs_linear_closure, double noise_level);

  bool two_pass() const { return two_pass_; }
  // The deconvolver of a pass, created from the registry: pass 1's the configured one at its fixed parameter; the
  // last pass's the configured one, or, after a choice for `channel`, the chosen parameter fixed.
  std::unique_ptr<Deconvolver> deconvolver(ClosurePass pass, const std::string& channel = "") const;
  // The rule applied once to `data` under `op` for `channel` ("" for a model with one closure): fixes that channel's
  // parameter (an integer one rounded) for the last pass and records the choice.
  void choose(const ForwardOperator& op, const Eigen::VectorXd& data, const std::string& channel = "");
  // The record of the two passes (the row's reduced_model.two_pass_rule): rule, parameter (its name),
  // pass_1_parameter (the configured value), pass_1_status (run_two_pass) and, for each channel (in the record
  // itself for ""), chosen, rule_status, rule_message and rule_note (a choice at the edge of the scan).
  json& record() { return record_; }
  const json& record() const { return record_; }

 private:
  const Registry& registry_;
  json configured_;
  bool two_pass_ = false;
  double noise_level_ = 0.0;
  std::map<std::string, json> chosen_;  // the last pass's deconvolver by channel
  json record_;
};

// A model run under the rule, the last pass's (its model kept for the caller's fields), with its times.
template <class Handle, class Result>
struct TwoPassRun {
  Handle model;
  Result result;
  double setup_seconds = 0.0;  // both passes' construction
  double loop_seconds = 0.0;   // pass 1's run, the choice and the last pass's run (each run's wall_seconds)
};

// One reduced run under `rule`. `build(pass)` constructs a model for that pass (taking its deconvolvers from
// rule.deconvolver(pass, channel)) and returns an owning handle whose ->run() gives a result with `status` and
// `wall_seconds`. With two passes, pass 1 is built and run, the record's pass_1_status set, and `choose(model,
// result)` calls rule.choose for each channel's operator and data; then the last pass is built and run.
template <class Build, class Choose>
auto run_two_pass(ClosureParameterRule& rule, Build&& build, Choose&& choose) {
  using Handle = decltype(build(ClosurePass::first));
  using Result = decltype(std::declval<Handle&>()->run());
  TwoPassRun<Handle, Result> out;
  if (rule.two_pass()) {
    const auto t0 = std::chrono::steady_clock::now();
    Handle first = build(ClosurePass::first);
    out.setup_seconds += seconds_since(t0);
    const Result r1 = first->run();
    const auto t1 = std::chrono::steady_clock::now();
    rule.record()["pass_1_status"] = row_status(r1.status);
    choose(*first, r1);
    out.loop_seconds += r1.wall_seconds + seconds_since(t1);
  }
  const auto t2 = std::chrono::steady_clock::now();
  out.model = build(ClosurePass::last);
  out.setup_seconds += seconds_since(t2);
  out.result = out.model->run();
  out.loop_seconds += out.result.wall_seconds;
  return out;
}

}  // namespace closurelab
