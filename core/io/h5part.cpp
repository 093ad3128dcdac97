#include "core/io/h5part.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "core/base/errors.hpp"
#include "core/io/hdf5_handle.hpp"
#include "core/base/memory_limit.hpp"

namespace closurelab {

namespace {

std::mutex& hdf5_mutex() {
  static std::mutex m;
  return m;
}

using Handle = detail::Hdf5Handle;

void silence_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }  // errors become exceptions here

std::string step_name(long long k) { return "Step#" + std::to_string(k); }

template <class T>
void write_dataset(hid_t group, const char* name, const std::vector<T>& data, hid_t file_type, hid_t mem_type,
                   const std::string& file) {
  const hsize_t dims[1] = {static_cast<hsize_t>(data.size())};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  Handle set(H5Dcreate2(group, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!space.ok() || !set.ok() ||
      (!data.empty() && H5Dwrite(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0))
    throw std::runtime_error("cannot write dataset '" + std::string(name) + "' to '" + file + "'");
}

// A 1D dataset converted to `mem_type`; false when the dataset does not exist.
template <class T>
bool read_dataset(hid_t group, const std::string& name, hid_t mem_type, std::vector<T>& out, const std::string& where) {
  if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0) return false;
  Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.ok()) throw ConfigError("", where + "/" + name + ": not a readable dataset");
  Handle space(H5Dget_space(set.get()), H5Sclose);
  if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 1)
    throw ConfigError("", where + "/" + name + ": not a one-dimensional dataset");
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  // A header may declare any size (1e12 particles ended in a bare std::bad_alloc): the declared size is
  // bounded before anything is allocated. A snapshot's particles then cost about kBytesPerParticle each in the
  // closure's pair sums, which read_step checks on `x` first.
  check_allocation(static_cast<double>(n), static_cast<double>(sizeof(T)),
                   where + "/" + name + ": " + std::to_string(n) + " values");
  out.assign(static_cast<std::size_t>(n), T{});
  if (n > 0 && H5Dread(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw ConfigError("", where + "/" + name + ": cannot read (truncated or corrupt file?)");
  return true;
}

// The end-of-file address the superblock declares (format spec §II.A; versions 0-3), or 0 when none is found.
// HDF5 1.10's H5Fopen on a file cut short of it fails and leaks the file's identifiers, so that the library prints
// "infinite loop closing library" and a line of E,E,E at exit: a truncated file is refused before it is opened.
std::uint64_t declared_end_of_file(const std::string& file, std::uint64_t size) {
  std::ifstream in(file, std::ios::binary);
  static const unsigned char signature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  for (std::uint64_t at = 0; at + 64 <= size; at = at == 0 ? 512 : 2 * at) {
    unsigned char b[64];
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(b), sizeof b)) return 0;
    if (!std::equal(signature, signature + 8, b)) continue;
    const int version = b[8];
    const int offsets = version <= 1 ? b[13] : b[9];
    if (version > 3 || (offsets != 4 && offsets != 8)) return 0;
    // The end-of-file address: the third address after the fixed fields (base, free-space or extension, EOF).
    const std::size_t fixed = version == 0 ? 24 : version == 1 ? 28 : 12;
    const std::size_t pos = fixed + 2 * static_cast<std::size_t>(offsets);
    std::uint64_t eof = 0;
    for (int k = offsets - 1; k >= 0; --k) eof = (eof << 8) | b[pos + k];
    return eof == ~std::uint64_t{0} ? 0 : at + eof;  // addresses are relative to the superblock's base
  }
  return 0;
}

Handle open_for_reading(const std::string& file) {
  silence_hdf5();
  if (H5Fis_hdf5(file.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw ConfigError("", "'" + file + "' is not a readable HDF5 file (missing, truncated or another format)");
  }
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(file, ec);
  if (const std::uint64_t eof = ec ? 0 : declared_end_of_file(file, size); eof > size)
    throw ConfigError("", "'" + file + "' is truncated: it has " + std::to_string(size) + " bytes, its superblock declares " +
                              std::to_string(eof));
  Handle f(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.ok()) {
    H5Eclear2(H5E_DEFAULT);
    throw ConfigError("", "cannot open HDF5 file '" + file + "' (truncated or corrupt?)");
  }
  return f;
}

// The Step#N links of the root group, by increasing N, with their TimeValue where the group has one.
std::vector<H5PartStep> list_steps(hid_t f, const std::string& file) {
  std::vector<H5PartStep> steps;
  auto visit = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    const std::string n = name;
    const std::string digits = n.size() > 5 && n.compare(0, 5, "Step#") == 0 ? n.substr(5) : "";
    if (!digits.empty() && digits.size() <= 18 && digits.find_first_not_of("0123456789") == std::string::npos) {
      H5PartStep s;
      s.number = std::stoll(digits);
      s.group = n;
      static_cast<std::vector<H5PartStep>*>(data)->push_back(s);
    }
    return 0;
  };
  hsize_t at = 0;
  if (H5Literate(f, H5_INDEX_NAME, H5_ITER_NATIVE, &at, visit, &steps) < 0)
    throw ConfigError("", "'" + file + "': cannot list its groups (truncated or corrupt file?)");
  std::sort(steps.begin(), steps.end(), [](const H5PartStep& a, const H5PartStep& b) { return a.number < b.number; });
  for (std::size_t i = 1; i < steps.size(); ++i)
    if (steps[i].number == steps[i - 1].number)
      throw ConfigError("", "'" + file + "': groups '" + steps[i - 1].group + "' and '" + steps[i].group +
                                "' both name step " + std::to_string(steps[i].number) + "; which one is meant is ambiguous");
  for (auto& s : steps) {
    if (H5Aexists_by_name(f, s.group.c_str(), "TimeValue", H5P_DEFAULT) <= 0) continue;
    Handle a(H5Aopen_by_name(f, s.group.c_str(), "TimeValue", H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    s.has_time = a.ok() && detail::holds_one_value(a.get()) && H5Aread(a.get(), H5T_NATIVE_DOUBLE, &s.time) >= 0 &&
                 std::isfinite(s.time);
  }
  return steps;
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// "3 steps: Step#0 (t = 0), Step#10 (t = 0.1), Step#20 (t = 0.2)", at most 8 listed.
std::string describe_steps(const std::vector<H5PartStep>& steps) {
  std::string d = std::to_string(steps.size()) + (steps.size() == 1 ? " step: " : " steps: ");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (i == 6 && steps.size() > 8) {
      d += ", ...";
      i = steps.size() - 2;
      continue;
    }
    d += (i == 0 ? "" : ", ") + steps[i].group + (steps[i].has_time ? " (t = " + short_number(steps[i].time) + ")" : "");
  }
  return d;
}

long long select_step(const std::vector<H5PartStep>& steps, H5PartStepBy by, long long value, double time,
                      const std::string& file) {
  if (steps.empty()) throw ConfigError("", "'" + file + "' holds no H5Part step (no group Step#N)");
  const std::string have = "'" + file + "' has " + describe_steps(steps);
  const std::string how = "; pick one by its number (step), by its place (step_by index, 0.." +
                          std::to_string(steps.size() - 1) + ") or by its time (step_by time)";
  switch (by) {
    case H5PartStepBy::number:
      if (value == -1) return steps.back().number;
      for (const auto& s : steps)
        if (s.number == value) return value;
      throw ConfigError("", have + "; there is no Step#" + std::to_string(value) + how);
    case H5PartStepBy::index:
      if (value == -1) return steps.back().number;
      if (value < 0 || value >= static_cast<long long>(steps.size()))
        throw ConfigError("", have + "; index " + std::to_string(value) + " is out of range" + how);
      return steps[static_cast<std::size_t>(value)].number;
    case H5PartStepBy::time: {
      std::vector<const H5PartStep*> match;
      const H5PartStep* nearest = nullptr;
      for (const auto& s : steps) {
        if (!s.has_time) continue;
        if (std::abs(s.time - time) <= 1e-9 * std::max(std::abs(s.time), std::abs(time))) match.push_back(&s);
        if (!nearest || std::abs(s.time - time) < std::abs(nearest->time - time)) nearest = &s;
      }
      if (match.size() == 1) return match[0]->number;
      if (match.size() > 1)
        throw ConfigError("", have + "; " + std::to_string(match.size()) + " steps have TimeValue " +
                                  short_number(time) + " (" + match[0]->group + ", " + match[1]->group +
                                  "): ambiguous; pick one by its number (step)");
      throw ConfigError("", have + "; none has TimeValue " + short_number(time) +
                                (nearest ? " (the nearest is " + nearest->group + " at t = " + short_number(nearest->time) + ")"
                                         : " (no step has a TimeValue)") + how);
    }
  }
  return steps.back().number;
}

ParticleSnapshot read_step(hid_t f, long long k, const std::string& file) {
  const std::string where = file + ":" + step_name(k);
  Handle g(H5Gopen2(f, step_name(k).c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.ok()) throw ConfigError("", where + ": not a readable group");
  ParticleSnapshot s;
  if (H5Aexists(g.get(), "TimeValue") > 0) {
    Handle a(H5Aopen(g.get(), "TimeValue", H5P_DEFAULT), H5Aclose);
    if (a.ok() && !detail::holds_one_value(a.get()))
      throw ConfigError("", where + ": attribute TimeValue is not a single value");
    if (!a.ok() || H5Aread(a.get(), H5T_NATIVE_DOUBLE, &s.time) < 0)
      throw ConfigError("", where + ": unreadable attribute TimeValue");
  }
  ParticleSystem& p = s.particles;
  if (H5Lexists(g.get(), "x", H5P_DEFAULT) > 0) {  // the particle count the file declares, bounded first
    Handle set(H5Dopen2(g.get(), "x", H5P_DEFAULT), H5Dclose);
    Handle space(set.ok() ? H5Dget_space(set.get()) : -1, H5Sclose);
    hsize_t n = 0;
    if (space.ok() && H5Sget_simple_extent_ndims(space.get()) == 1) H5Sget_simple_extent_dims(space.get(), &n, nullptr);
    check_allocation(static_cast<double>(n), kBytesPerParticle,
                     where + "/x: a snapshot of " + std::to_string(n) + " particles");
  }
  for (auto [name, v] : {std::pair{"x", &p.x}, {"y", &p.y}, {"vx", &p.vx}, {"vy", &p.vy}, {"mass", &p.mass}})
    if (!read_dataset(g.get(), name, H5T_NATIVE_DOUBLE, *v, where))
      throw ConfigError("", where + ": no dataset '" + std::string(name) + "' (needed: x, y, vx, vy, mass)");
  // Phases are read as doubles and checked: HDF5's conversion to int truncates 0.5 to 0 and clips 2^63 to
  // 2147483647 without a word.
  std::vector<double> phase;
  if (read_dataset(g.get(), "phase", H5T_NATIVE_DOUBLE, phase, where)) {
    p.phase.resize(phase.size());
    for (std::size_t k = 0; k < phase.size(); ++k) {
      if (!(phase[k] >= 0 && phase[k] <= 2147483647.0 && phase[k] == std::floor(phase[k])))
        throw ConfigError("", where + "/phase: entry " + std::to_string(k) + " = " + short_number(phase[k]) +
                                  " is not a phase index (an integer from 0 to 2147483647)");
      p.phase[k] = static_cast<int>(phase[k]);
    }
  } else {
    p.phase.assign(p.x.size(), 0);
  }
  s.has_fixed = read_dataset(g.get(), "fixed", H5T_NATIVE_UINT8, p.fixed, where);
  if (!s.has_fixed) p.fixed.assign(p.x.size(), 0);
  check_particles(p, where);
  return s;
}

}  // namespace

void write_h5part(const std::string& file, const std::vector<ParticleSnapshot>& steps) {
  std::lock_guard<std::mutex> lock(hdf5_mutex());
  silence_hdf5();
  Handle f(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.ok()) throw std::runtime_error("cannot create HDF5 file '" + file + "'");
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const ParticleSystem& p = steps[k].particles;
    Handle g(H5Gcreate2(f.get(), step_name(static_cast<int>(k)).c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Gclose);
    Handle scalar(H5Screate(H5S_SCALAR), H5Sclose);
    Handle a(H5Acreate2(g.get(), "TimeValue", H5T_IEEE_F64LE, scalar.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    if (!g.ok() || !a.ok() || H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &steps[k].time) < 0)
      throw std::runtime_error("cannot write step " + std::to_string(k) + " to '" + file + "'");
    const std::vector<double> zeros(p.size(), 0.0);
    for (auto [name, v] : {std::pair{"x", &p.x}, {"y", &p.y}, {"z", &zeros}, {"vx", &p.vx}, {"vy", &p.vy},
                           {"mass", &p.mass}})
      write_dataset(g.get(), name, *v, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, file);
    const std::vector<std::int32_t> phase(p.phase.begin(), p.phase.end());
    write_dataset(g.get(), "phase", phase, H5T_STD_I32LE, H5T_NATIVE_INT32, file);
    write_dataset(g.get(), "fixed", p.fixed, H5T_STD_U8LE, H5T_NATIVE_UINT8, file);
  }
  if (H5Fflush(f.get(), H5F_SCOPE_GLOBAL) < 0) throw std::runtime_error("cannot flush '" + file + "'");
}

std::vector<H5PartStep> h5part_steps(const std::string& file) {
  std::lock_guard<std::mutex> lock(hdf5_mutex());
  const Handle f = open_for_reading(file);
  return list_steps(f.get(), file);
}

int h5part_step_count(const std::string& file) { return static_cast<int>(h5part_steps(file).size()); }

long long h5part_select_step(const std::string& file, H5PartStepBy by, long long value, double time) {
  return select_step(h5part_steps(file), by, value, time, file);
}

ParticleSnapshot read_h5part(const std::string& file, long long step) {
  std::lock_guard<std::mutex> lock(hdf5_mutex());
  const Handle f = open_for_reading(file);
  const long long number = select_step(list_steps(f.get(), file), H5PartStepBy::number, step, 0.0, file);
  return read_step(f.get(), number, file);
}

std::vector<ParticleSnapshot> read_h5part_all(const std::string& file) {
  std::lock_guard<std::mutex> lock(hdf5_mutex());
  const Handle f = open_for_reading(file);
  std::vector<ParticleSnapshot> out;
  for (const auto& s : list_steps(f.get(), file)) out.push_back(read_step(f.get(), s.number, file));
  return out;
}

}  // namespace closurelab
