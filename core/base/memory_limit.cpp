#include "core/base/memory_limit.hpp"

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/base/errors.hpp"

namespace closurelab {

namespace {

std::uint64_t g_memory_limit = 0;  // set_memory_limit_bytes; 0: not set
std::uint64_t g_max_cells = 0;     // set_max_cells; 0: not set

std::uint64_t physical_half() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t{8} << 30;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2;
}

const char* env_value(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? v : nullptr;
}

// A positive decimal count (digits only), for CLOSURELAB_MAX_CELLS and --max-cells.
std::uint64_t parse_count(const std::string& text, const std::string& what) {
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    throw ConfigError(what, "expected a positive whole number of cells, got '" + text + "'");
  const std::uint64_t n = std::stoull(text);
  if (n == 0) throw ConfigError(what, "expected a positive whole number of cells, got '" + text + "'");
  return n;
}

}  // namespace

std::uint64_t parse_byte_count(const std::string& text, const std::string& what) {
  std::size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.' || text[i] == 'e' ||
                             text[i] == 'E' || text[i] == '+'))
    ++i;
  std::string number = text.substr(0, i), unit = text.substr(i);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  const auto bad = [&] {
    return ConfigError(what, "expected a memory size such as 8GB, 512MiB or 1e9 (bytes), got '" + text + "'");
  };
  if (number.empty() || !std::isdigit(static_cast<unsigned char>(number.front()))) throw bad();
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (end != number.c_str() + number.size() || !std::isfinite(value) || !(value > 0)) throw bad();
  static const std::pair<const char*, double> units[] = {
      {"", 1.0},      {"B", 1.0},     {"kB", 1e3},           {"KB", 1e3},           {"MB", 1e6},
      {"GB", 1e9},    {"TB", 1e12},   {"KiB", 1024.0},       {"MiB", 1048576.0},    {"GiB", 1073741824.0},
      {"TiB", 1099511627776.0}};
  for (const auto& [name, factor] : units)
    if (unit == name) {
      const double bytes = value * factor;
      if (!(bytes >= 1.0) || bytes > 1.8e19) throw bad();
      return static_cast<std::uint64_t>(bytes);
    }
  throw bad();
}

std::uint64_t memory_limit_bytes() {
  if (g_memory_limit) return g_memory_limit;
  if (const char* v = env_value("CLOSURELAB_MEMORY_LIMIT")) return parse_byte_count(v, "CLOSURELAB_MEMORY_LIMIT");
  return physical_half();
}

std::string memory_limit_source() {
  if (g_memory_limit) return "--memory-limit";
  if (env_value("CLOSURELAB_MEMORY_LIMIT")) return "CLOSURELAB_MEMORY_LIMIT";
  return "half the physical memory; --memory-limit or CLOSURELAB_MEMORY_LIMIT sets another";
}

void set_memory_limit_bytes(std::uint64_t bytes) { g_memory_limit = bytes; }

std::uint64_t max_cells() {
  if (g_max_cells) return g_max_cells;
  if (const char* v = env_value("CLOSURELAB_MAX_CELLS")) return parse_count(v, "CLOSURELAB_MAX_CELLS");
  return kDefaultMaxCells;
}

std::string max_cells_source() {
  if (g_max_cells) return "--max-cells";
  if (env_value("CLOSURELAB_MAX_CELLS")) return "CLOSURELAB_MAX_CELLS";
  return "the default; --max-cells or CLOSURELAB_MAX_CELLS sets another";
}

void set_max_cells(std::uint64_t cells) { g_max_cells = cells; }

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
                                format_bytes(limit) + " (" + memory_limit_source() + ")");
}

void check_particle_memory(long nx, long ny, const std::string& path) {
  check_allocation(static_cast<double>(nx) * static_cast<double>(ny), kBytesPerParticle,
                   "a direct SPH run of n_x * n_y = " + std::to_string(nx) + " * " + std::to_string(ny) + " particles",
                   path);
}

namespace {

std::string count_text(double n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, n < 1e9 ? "%.0f" : "%.3g", n);
  return buf;
}

}  // namespace

double force_density_2d_bytes(double coarse_nodes, double reconstruction_nodes, bool x_invariant) {
  const double nc = coarse_nodes, nr = reconstruction_nodes;
  const double system = x_invariant ? nc : 3.0 * nc;
  return sizeof(double) * (11.0 * nc * nr + 2.0 * system * system);
}

void check_force_density_2d_memory(double coarse_nodes, double reconstruction_nodes, bool x_invariant,
                                   const std::string& path) {
  check_allocation(force_density_2d_bytes(coarse_nodes, reconstruction_nodes, x_invariant), 1.0,
                   "the 2D force-density model's dense maps and steady system (" + count_text(coarse_nodes) +
                       " coarse x " + count_text(reconstruction_nodes) + " reconstruction nodes)",
                   path);
}

void check_mesh_2d_memory(double nx, double ny, const std::string& path) {
  const double doubles = nx * nx + ny * ny + kDoublesPerMesh2DNode * nx * ny;
  check_allocation(doubles, sizeof(double),
                   "the 2D reduced model's coarse mesh of " + count_text(nx) + " x " + count_text(ny) +
                       " nodes (its kernel matrices and fields)",
                   path);
}

}  // namespace closurelab
