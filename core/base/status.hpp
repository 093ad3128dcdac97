#pragma once
// The one status vocabulary of every computation: a time-stepping run (direct SPH, reduced model) ends
// converged (steady state), at its target time, without convergence, or with a numerical issue; a deconvolution
// ends converged, without convergence, or with a numerical issue. Non-convergence is a result, not an error
// (DESIGN.md); a row of a table is "ok" when its run is a result (converged or at its target time).
#include <array>
#include <string_view>
#include <utility>

#include "core/base/enum_names.hpp"

namespace closurelab {

enum class Status { converged, target_time, no_convergence, numerical_issue };

template <>
struct EnumNames<Status> {
  static constexpr std::array<std::pair<Status, std::string_view>, 4> table{
      {{Status::converged, "converged"},
       {Status::target_time, "target_time"},
       {Status::no_convergence, "no_convergence"},
       {Status::numerical_issue, "numerical_issue"}}};
};

inline std::string to_string(Status s) { return name_of(s); }
// A table row's status: "ok" for a result, else the status's name.
inline std::string row_status(Status s) {
  return s == Status::converged || s == Status::target_time ? "ok" : to_string(s);
}

}  // namespace closurelab
