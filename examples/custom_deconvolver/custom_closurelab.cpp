// closurelab's command line with the user's Richardson iteration registered: `custom_closurelab list
// deconvolver`, `custom_closurelab run SPEC.json --out DIR` (a spec may name "richardson" wherever a
// deconvolver goes), `custom_closurelab deconvolve ... --method richardson`.
#include "experiments/runner/closurelab_main.hpp"
#include "richardson.hpp"

int main(int argc, char** argv) {
  return closurelab::closurelab_main(argc, argv, closurelab_example::register_richardson);
}
