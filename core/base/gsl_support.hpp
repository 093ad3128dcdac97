#pragma once
// GSL aborts the process on errors by default; closurelab turns that off once and checks status codes.
namespace closurelab {
void gsl_errors_as_status();
}
