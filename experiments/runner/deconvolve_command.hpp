#pragma once
// `closurelab deconvolve --matrix A.mtx --rhs b.mtx ...`: deconvolution of a user system (deconvolution issue).
namespace closurelab {
int run_deconvolve_command(int argc, char** argv);
}
