#include "experiments/sph_validation.hpp"

namespace closurelab {
namespace {
class SphValidation : public ExperimentKind {
 public:
  std::string name() const override { return "direct_sph_validation"; }
  std::string description() const override { return "direct SPH to steady state vs analytic"; }
  json resolve(const json& cell, const std::string&, const Registry&) const override { return cell; }
  json run(const json&, const Registry&, const ProgressFn&) const override { return json::object(); }
};
}  // namespace
std::unique_ptr<ExperimentKind> make_sph_validation_experiment() { return std::make_unique<SphValidation>(); }
}  // namespace closurelab
