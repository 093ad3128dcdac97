#include "core/base/memory_limit.hpp"

#include <unistd.h>

#include <cstdio>

#include "core/base/errors.hpp"

namespace closurelab {

std::uint64_t memory_limit_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t{8} << 30;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 6) {
    bytes /= 1000.0;
    ++u;
  }
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.1f %s", bytes, units[u]);
  return buf;
}

void check_allocation(double count, double bytes_per_item, const std::string& what, const std::string& path) {
  const double need = count * bytes_per_item;  // doubles: no wrap-around for any size
  const double limit = static_cast<double>(memory_limit_bytes());
  if (!(need <= limit))
    throw ConfigError(path, what + " needs about " + format_bytes(need) + ", above the memory limit of " +
                                format_bytes(limit) + " (half the physical memory)");
}

void check_particle_memory(long nx, long ny, const std::string& path) {
  check_allocation(static_cast<double>(nx) * static_cast<double>(ny), kBytesPerParticle,
                   "a direct SPH run of n_x * n_y = " + std::to_string(nx) + " * " + std::to_string(ny) + " particles",
                   path);
}

}  // namespace closurelab
