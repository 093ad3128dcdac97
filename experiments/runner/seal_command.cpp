#include "experiments/runner/seal_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include "experiments/runner/out_folder.hpp"
#include "experiments/runner/results_table.hpp"

namespace closurelab {

namespace fs = std::filesystem;

const CommandSpec& seal_command_spec() {
  static const CommandSpec spec{
      "seal",
      {{"DIR"}},
      "  Adds the checksum cell_fnv1a64 to every cell file of DIR/cells that has none (written by an older\n"
      "  closurelab), the row unchanged: a run and `merge` refuse a cell file without it as edited. Seal only a\n"
      "  folder whose cells you trust. Names each file whose formatting changes beyond the added key and each it\n"
      "  cannot seal (unreadable, not a cell's row, a checksum that does not match: left as it is).",
      {{"--dry-run", "", "write nothing: list what sealing would do"}},
      "  Exit codes: 0 every cell file sealed (or already), 1 a write failed, 2 a file could not be sealed, no\n"
      "  DIR/cells, bad input or the folder in use."};
  return spec;
}

int run_seal_command(int argc, char** argv) {
  if (wants_help(seal_command_spec(), argc, argv)) {
    std::cout << usage(seal_command_spec());
    return 0;
  }
  const ParsedArgs args = parse_command_line(seal_command_spec(), argc, argv);
  const std::string dir = args.positional(0);
  const bool write = !args.has("--dry-run");
  const fs::path cells_dir = fs::path(dir) / "cells";
  std::error_code ec;
  if (!fs::is_directory(cells_dir, ec)) {
    std::cerr << "error: no folder '" << cells_dir.string() << "': seal takes a run's output folder (--out DIR)\n";
    return 2;
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(cells_dir))
    if (e.path().extension() == ".json" && !e.is_directory()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::unique_ptr<FolderLock> lock;  // no run may write the cells meanwhile
  if (write) {
    std::string command_line;
    for (int i = 0; i < argc; ++i) command_line.append(i ? " " : "").append(argv[i]);
    try {
      lock = std::make_unique<FolderLock>(dir, command_line);
    } catch (const FolderBusy& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 2;
    }
  }
  std::size_t sealed = 0, already = 0, reformatted = 0, refused = 0;
  for (const fs::path& f : files) {
    SealOutcome s;
    try {
      s = seal_cell_file(f, write);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\nerror: " << sealed << " cell file(s) sealed before the failure\n";
      return 1;
    }
    switch (s.result) {
      case SealOutcome::Result::sealed:
        ++sealed;
        if (s.formatting_changed) {
          ++reformatted;
          std::cerr << "note: " << f.string() << ": its formatting " << (write ? "changed" : "would change")
                    << " (rewritten as closurelab writes a cell file); its row reads back unchanged\n";
        }
        break;
      case SealOutcome::Result::already_sealed: ++already; break;
      case SealOutcome::Result::refused:
        ++refused;
        std::cerr << "error: " << f.string() << " " << s.problem << "; not sealed\n";
        break;
    }
  }
  std::cerr << "[seal] " << cells_dir.string() << ": " << sealed << " cell file(s) " << (write ? "sealed" : "to seal")
            << " (" << reformatted << " with other formatting), " << already << " already sealed, " << refused
            << " not sealed\n";
  return refused == 0 ? 0 : 2;
}

}  // namespace closurelab
