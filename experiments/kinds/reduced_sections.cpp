#include "experiments/kinds/reduced_sections.hpp"

#include <cmath>

#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"

namespace closurelab {

ParamSchema closure_schema() {
  return {object_param("deconvolver", json{{"name", "landweber"}, {"order", 0}}, "registered deconvolver and its parameters"),
          string_param("discretization", "coarse_coarse", "discretization of R_eta (par. 4.2)",
                       names_of<Discretization>()),
          number_param("noise_level", 0.0, "delta handed to the deconvolver's parameter rule", 0.0, {})};
}

ParamSchema reference_schema() {
  return {bool_param("direct_sph", true, "run the direct SPH of the same scene as a reference (and for the speed-up)"),
          object_param("solver", json::object(), "direct SPH solver parameters (as in direct_sph_validation)"),
          number_param("observe_spacing_over_eta", 0.25, "mesh spacing / eta' for the direct run's steady test", 0.01, 10.0)};
}

void check_snapshot_times(const json& times, const std::string& path) {
  double previous = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const json& t = times[k];
    if (!t.is_number() || !std::isfinite(t.get<double>()) || t.get<double>() <= previous)
      throw ConfigError(path + "/" + std::to_string(k), "snapshot times must be finite numbers, positive and ascending");
    previous = t.get<double>();
  }
}

}  // namespace closurelab
