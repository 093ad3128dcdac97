// closurelab: the stock command-line entry point (the built-in strategies only). A user's executable calls
// closurelab_main with its own registration hook instead (examples/custom_deconvolver/).
#include "experiments/runner/closurelab_main.hpp"

int main(int argc, char** argv) { return closurelab::closurelab_main(argc, argv); }
