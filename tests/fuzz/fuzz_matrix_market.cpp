// libFuzzer target: the Matrix Market reader on arbitrary bytes (written to a scratch file, since the reader
// takes a path). Anything but a clean ConfigError is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/base/errors.hpp"
#include "core/io/matrix_market.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string file = "/tmp/closurelab_fuzz_mm_" + std::to_string(getpid()) + ".mtx";
  if (std::FILE* f = std::fopen(file.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  try {
    closurelab::read_matrix_market(file);
  } catch (const closurelab::ConfigError&) {
  }
  return 0;
}
