#include "core/reduced/closure_rule.hpp"

#include <cmath>

#include "core/closure/forward_operator.hpp"

namespace closurelab {

namespace {

constexpr const char* deconvolver_path = "/closure/deconvolver";

bool has_rule(const json& deconvolver) { return deconvolver.value("rule", "fixed") != "fixed"; }

json at_fixed_rule(json deconvolver) {
  deconvolver["rule"] = "fixed";
  return deconvolver;
}

}  // namespace

bool ClosureParameterRule::applies(const json& resolved_deconvolver, bool model_needs_linear_closure) {
  return model_needs_linear_closure && has_rule(resolved_deconvolver);
}

ClosureParameterRule::ClosureParameterRule(const Registry& registry, json configured, bool model_needs_linear_closure,
                                           double noise_level)
    : registry_(registry),
      configured_(std::move(configured)),
      two_pass_(applies(configured_, model_needs_linear_closure)),
      noise_level_(noise_level) {
  if (two_pass_) record_["rule"] = configured_.at("rule");
}

std::unique_ptr<Deconvolver> ClosureParameterRule::deconvolver(ClosurePass pass, const std::string& channel) const {
  if (pass == ClosurePass::first && two_pass_) return registry_.deconvolvers.create(at_fixed_rule(configured_), deconvolver_path);
  const auto chosen = chosen_.find(channel);
  return registry_.deconvolvers.create(chosen == chosen_.end() ? configured_ : chosen->second, deconvolver_path);
}

void ClosureParameterRule::choose(const ForwardOperator& op, const Eigen::VectorXd& data, const std::string& channel) {
  auto rule = registry_.deconvolvers.create(configured_, deconvolver_path);
  rule->setup(op);
  const DeconvolutionResult c = rule->solve(data, noise_level_);
  const std::string& name = c.stats.parameter_name;
  json fixed = at_fixed_rule(configured_);
  if (fixed.contains(name) && fixed.at(name).is_number_integer())
    fixed[name] = std::lround(c.stats.chosen_parameter);
  else
    fixed[name] = c.stats.chosen_parameter;
  record_["parameter"] = name;
  record_["pass_1_parameter"] = configured_.value(name, json());
  json& into = channel.empty() ? record_ : record_[channel];
  into["chosen"] = fixed.at(name);
  into["rule_status"] = row_status(c.status);
  into["rule_message"] = c.stats.message;
  if (!c.stats.note.empty()) into["rule_note"] = c.stats.note;
  chosen_[channel] = std::move(fixed);
}

}  // namespace closurelab
