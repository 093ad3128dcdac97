#pragma once
// The closurelab command line (list, run, merge, deconvolve, --help, --version) as a library function, so that a
// user's executable runs the same specs with its own strategies (as PETSc's KSPRegister does for user solvers):
//
//   int main(int argc, char** argv) {
//     return closurelab::closurelab_main(argc, argv, [](closurelab::Registry& r) {
//       r.deconvolvers.add({"richardson", "...", richardson_schema()}, make_richardson);
//     });
//   }
//
// The registry holds the built-ins (register_builtin_strategies), then whatever `register_user` adds; every
// command (list, run, merge, deconvolve) sees that one registry. A name registered twice is a std::logic_error
// (exit 1). Returns the process exit code (0 ok, 1 a failure, 2 bad input).
#include <functional>

#include "core/base/registry.hpp"

namespace closurelab {

using UserRegistration = std::function<void(Registry&)>;

int closurelab_main(int argc, char** argv, const UserRegistration& register_user = {});

}  // namespace closurelab
