#pragma once
// `closurelab seal DIR [--dry-run]`: adds `cell_fnv1a64` (results_table.hpp) to every cell file DIR/cells/*.json
// that lacks it, its row unchanged, so that cells written before cells carried the checksum (the committed results)
// are reused and merged again. A run and `merge` take a file without the key for an edited one; sealing says the
// folder's old cells are trusted. A file whose bytes were not closurelab's own dump of its row is named (its
// formatting changes beyond the added key); one that cannot be sealed (unreadable, not a cell's row, a checksum
// that does not match) is named and left as it is.
#include "experiments/runner/command_options.hpp"

namespace closurelab {

// Its options (command_options.hpp).
const CommandSpec& seal_command_spec();
int run_seal_command(int argc, char** argv);

}  // namespace closurelab
