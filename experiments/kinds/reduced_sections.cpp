#include "experiments/kinds/reduced_sections.hpp"

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

}  // namespace closurelab
