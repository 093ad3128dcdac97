// libFuzzer target: the CSV particle-snapshot reader (core/io/particle_snapshot.hpp, a snapshot from another
// code) on arbitrary bytes, written to a scratch .csv file since the reader takes a path. Anything but a clean
// ConfigError is a finding. (The H5Part and PySPH readers are not fuzzed on arbitrary bytes: they hand the file
// to the HDF5 library, whose own parser is not hardened against malformed files and is not instrumented here.
// fuzz_hdf5_snapshot.cpp fuzzes them on valid HDF5 files of arbitrary structure and content instead.)
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/base/errors.hpp"
#include "core/io/particle_snapshot.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string file = "/tmp/closurelab_fuzz_csv_" + std::to_string(getpid()) + ".csv";
  if (std::FILE* f = std::fopen(file.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  try {
    closurelab::read_particle_snapshot(file, -1);
  } catch (const closurelab::ConfigError&) {
  }
  return 0;
}
