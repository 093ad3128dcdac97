#include "core/base/gsl_support.hpp"

#include <gsl/gsl_errno.h>

namespace closurelab {
void gsl_errors_as_status() {
  static const bool done = [] {
    gsl_set_error_handler_off();
    return true;
  }();
  (void)done;
}
}  // namespace closurelab
