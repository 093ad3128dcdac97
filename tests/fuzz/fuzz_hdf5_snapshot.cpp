// libFuzzer target: the HDF5 particle-snapshot readers (core/io/h5part.hpp, core/io/pysph_output.hpp, and
// read_particle_snapshot's dispatch between them), structure-aware. The HDF5 library's own parser is not
// hardened against malformed files (see fuzz_particle_csv.cpp), so the bytes are not the file: they are decoded
// into a description of a *valid* HDF5 file, which is written here with the HDF5 C API and then read with the
// public readers. Anything but a clean ConfigError is a finding.
//
// Decoding: structure bytes are taken from the front of the input, values from the back (so that mutating one
// leaves the other in place); an exhausted input reads as 0 bytes for the structure and as plausible values
// (positions 0.01 i, masses 1, phases/tags/flags 0), so short inputs describe valid files. The description:
//   header      layout (H5Part Step#N groups / PySPH /particles + /solver_data / both), the extension (.h5part,
//               .h5, .hdf5), /solver_data or /particles missing or a dataset, an unrelated root group;
//   H5Part      0-4 steps Step#N (N small, with leading zeros, huge, or names the reader must skip), each a group,
//               a dataset or a soft link, with or without TimeValue;
//   PySPH       0-3 particle arrays named fluid, solid, wall, ... with or without their `arrays` group;
//   datasets    the names the readers look for (each may be left out) plus others; each double, float, int32,
//               int64, uint8, a fixed-length string, big-endian double or int16; scalar, 1D (lengths may disagree,
//               may be 0) or 2D/3D; or a group, a dangling soft link, a soft link, an external link in its place;
//               rarely a chunked dataset declaring 2^31.. elements with nothing written; at most 4096 values in all;
//   attributes  TimeValue, t, dt, count, stored: scalar of any of those types, a string, or an array;
//   values      small positive and negative numbers, 0, -0, NaN, +-Inf, +-1e308, denormals, 2^31, 2^63, raw bits,
//               or (0xFD) the plausible value.
// The readers' memory limit is set to 512 MiB (below -rss_limit_mb): a declared size beyond it must be refused.
#include <hdf5.h>
#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/io/h5part.hpp"
#include "core/io/hdf5_handle.hpp"
#include "core/io/particle_snapshot.hpp"
#include "core/io/pysph_output.hpp"

namespace {

using closurelab::detail::Hdf5Handle;

// Structure from the front, values from the back; the two stop where they meet.
struct Input {
  const std::uint8_t* p;
  std::size_t lo, hi;
  std::uint8_t front() { return lo < hi ? p[lo++] : 0; }
  bool back(std::uint8_t& b) {
    if (lo >= hi) return false;
    b = p[--hi];
    return true;
  }
};

enum class Role { coordinate, mass, integer, time };

Role role_of(const std::string& name) {
  if (name == "mass" || name == "m" || name == "h" || name == "rho") return Role::mass;
  if (name == "phase" || name == "tag" || name == "fixed" || name == "stored" || name == "gid" || name == "pid")
    return Role::integer;
  return Role::coordinate;
}

double value(Input& in, Role role, std::size_t i) {
  std::uint8_t b = 0;
  if (!in.back(b) || b == 0xFD) {  // exhausted, or 0xFD: the plausible value
    switch (role) {
      case Role::mass: return 1.0;
      case Role::integer: return 0.0;
      case Role::time: return 0.1 * static_cast<double>(i);
      case Role::coordinate: return 0.01 * static_cast<double>(i);
    }
    return 0.0;
  }
  if (b < 100) return 0.05 * b;
  if (b < 200) return -0.05 * (b - 99);
  const double inf = std::numeric_limits<double>::infinity();
  const double special[] = {std::nan(""), inf, -inf, 1e308, -1e308, 0.0, -0.0, 4.9e-324, 2147483648.0,
                            9223372036854775808.0, -2147483649.0, 0.5, 1e-300, 255.5, 256.0, 1e19, -1.0, 3.0};
  if (b - 200u < sizeof special / sizeof special[0]) return special[b - 200];
  if (b >= 0xFE) {  // raw bits of a double (0xFE) or an int64 (0xFF)
    std::uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) {
      std::uint8_t c = 0;
      in.back(c);
      bits = (bits << 8) | c;
    }
    if (b == 0xFE) {
      double d;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
    return static_cast<double>(static_cast<std::int64_t>(bits));
  }
  return 1.0 + (b - 200);
}

template <class I>
I saturate(double d) {
  constexpr I lo = std::numeric_limits<I>::min(), hi = std::numeric_limits<I>::max();
  if (std::isnan(d)) return lo;
  if (d <= static_cast<double>(lo)) return lo;
  if (d >= static_cast<double>(hi)) return hi;
  return static_cast<I>(d);
}

float to_float(double d) {
  if (std::isnan(d)) return std::numeric_limits<float>::quiet_NaN();
  if (std::fabs(d) > FLT_MAX) return d > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
  return static_cast<float>(d);
}

enum class Ty { f64, f32, i32, i64, u8, str, f64be, i16be };

// Writes `count` values of type `ty` through `write(mem_type, buffer)` (a dataset's or an attribute's).
template <class Write>
void write_values(Ty ty, std::size_t count, Input& in, Role role, hid_t str_type, Write write) {
  std::vector<double> d(count);
  for (std::size_t i = 0; i < count; ++i) d[i] = value(in, role, i);
  switch (ty) {
    case Ty::f64:
    case Ty::f64be: write(H5T_NATIVE_DOUBLE, static_cast<const void*>(d.data())); break;
    case Ty::f32: {
      std::vector<float> v(count);
      for (std::size_t i = 0; i < count; ++i) v[i] = to_float(d[i]);
      write(H5T_NATIVE_FLOAT, static_cast<const void*>(v.data()));
      break;
    }
    case Ty::i32: {
      std::vector<std::int32_t> v(count);
      for (std::size_t i = 0; i < count; ++i) v[i] = saturate<std::int32_t>(d[i]);
      write(H5T_NATIVE_INT32, static_cast<const void*>(v.data()));
      break;
    }
    case Ty::i64: {
      std::vector<std::int64_t> v(count);
      for (std::size_t i = 0; i < count; ++i) v[i] = saturate<std::int64_t>(d[i]);
      write(H5T_NATIVE_INT64, static_cast<const void*>(v.data()));
      break;
    }
    case Ty::u8: {
      std::vector<std::uint8_t> v(count);
      for (std::size_t i = 0; i < count; ++i) v[i] = saturate<std::uint8_t>(d[i]);
      write(H5T_NATIVE_UINT8, static_cast<const void*>(v.data()));
      break;
    }
    case Ty::i16be: {
      std::vector<std::int16_t> v(count);
      for (std::size_t i = 0; i < count; ++i) v[i] = saturate<std::int16_t>(d[i]);
      write(H5T_NATIVE_INT16, static_cast<const void*>(v.data()));
      break;
    }
    case Ty::str: {
      std::vector<char> v(count * 8, '\0');
      for (std::size_t i = 0; i < count; ++i) std::snprintf(&v[i * 8], 8, "%g", d[i]);
      write(str_type, static_cast<const void*>(v.data()));
      break;
    }
  }
}

hid_t file_type(Ty ty) {
  switch (ty) {
    case Ty::f64: return H5T_IEEE_F64LE;
    case Ty::f32: return H5T_IEEE_F32LE;
    case Ty::i32: return H5T_STD_I32LE;
    case Ty::i64: return H5T_STD_I64LE;
    case Ty::u8: return H5T_STD_U8LE;
    case Ty::f64be: return H5T_IEEE_F64BE;
    case Ty::i16be: return H5T_STD_I16BE;
    case Ty::str: break;
  }
  return -1;
}

Hdf5Handle string_type() {
  Hdf5Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  if (t.ok()) H5Tset_size(t.get(), 8);
  return t;
}

struct Writer {
  Input& in;
  std::size_t budget = 4096;  // values left to write in this file

  std::size_t take(std::size_t n) {
    if (n > budget) return 0;
    budget -= n;
    return n;
  }

  // An attribute from one spec byte: scalar double, float, int32, int64, string or uint8, or a 1D (0-3) or
  // 2D (2 x 0-2) array of doubles.
  void attribute(hid_t loc, const char* name, std::uint8_t spec, Role role) {
    static const Ty kinds[] = {Ty::f64, Ty::f32, Ty::i32, Ty::i64, Ty::str, Ty::f64, Ty::u8, Ty::f64};
    const int kind = spec & 7;
    const Ty ty = kinds[kind];
    hsize_t dims[2] = {static_cast<hsize_t>((spec >> 3) % 4), 2};
    int rank = 0;
    if (kind == 5) rank = 1;
    if (kind == 7) {
      rank = 2;
      dims[0] = 2;
      dims[1] = (spec >> 3) % 3;
    }
    Hdf5Handle space(rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, nullptr), H5Sclose);
    const Hdf5Handle str = string_type();
    Hdf5Handle a(H5Acreate2(loc, name, ty == Ty::str ? str.get() : file_type(ty), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 H5Aclose);
    if (!a.ok()) return;
    const std::size_t count = rank == 0 ? 1 : static_cast<std::size_t>(dims[0] * (rank == 2 ? dims[1] : 1));
    if (count > 0 && take(count) == count)
      write_values(ty, count, in, role, str.get(), [&](hid_t mem, const void* buf) { H5Awrite(a.get(), mem, buf); });
  }

  void scalar_attribute(hid_t loc, const char* name, double v) {
    Hdf5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Hdf5Handle a(H5Acreate2(loc, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    if (a.ok()) H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &v);
  }

  void int_attribute(hid_t loc, const char* name, std::int64_t v) {
    Hdf5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Hdf5Handle a(H5Acreate2(loc, name, H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    if (a.ok()) H5Awrite(a.get(), H5T_NATIVE_INT64, &v);
  }

  // Something other than a dataset under `name`: a group, a dangling soft link, a soft link to `target`, or an
  // external link into a file that does not exist.
  void odd_object(hid_t loc, const std::string& name, std::uint8_t kind, const std::string& target) {
    switch (kind % 4) {
      case 0: {
        Hdf5Handle g(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
        break;
      }
      case 1: H5Lcreate_soft("/no/such/object", loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT); break;
      case 2: H5Lcreate_soft(target.c_str(), loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT); break;
      case 3:
        H5Lcreate_external("/tmp/closurelab_fuzz_no_such_file.h5", "/x", loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
        break;
    }
  }

  // One dataset. variant < 128: `n` doubles (the usual form); else bits 0-2 the type, bits 3-4 the shape (1D of
  // length n, 1D of a length from the next byte, scalar, 2D/3D), bit 5 a `stored` attribute, bit 6 not a dataset.
  void dataset(hid_t loc, const std::string& name, std::uint8_t variant, std::size_t n, bool stored_attribute,
               const std::string& target) {
    Ty ty = Ty::f64;
    int rank = 1;
    hsize_t dims[3] = {n, 1, 1};
    bool huge = false, attr = false;
    std::uint8_t attr_spec = 2;  // scalar int32
    if (variant >= 128) {
      if (variant & 64) return odd_object(loc, name, in.front(), target);
      ty = static_cast<Ty>(variant & 7);
      switch ((variant >> 3) & 3) {
        case 0: break;
        case 1: {
          const std::uint8_t l = in.front();
          if (l >= 0xF8) {
            huge = true;
            dims[0] = hsize_t{1} << (31 + 2 * (l & 7));
          } else {
            dims[0] = l % 65;
          }
          break;
        }
        case 2: rank = 0; break;
        case 3: {
          const std::uint8_t r = in.front();
          rank = 2 + (r & 1);
          for (int k = 0; k < rank; ++k) dims[k] = in.front() % 6;
          break;
        }
      }
      if (variant & 32) {
        attr = true;
        attr_spec = in.front();
      }
    }
    std::size_t count = 1;
    for (int k = 0; k < rank; ++k) count *= static_cast<std::size_t>(dims[k]);
    if (!huge && take(count) != count) {  // over the budget: an empty dataset of the same rank
      for (int k = 0; k < rank; ++k) dims[k] = 0;
      count = rank == 0 ? 1 : 0;
      if (rank == 0 && take(1) != 1) return;
    }
    Hdf5Handle space(rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims, nullptr), H5Sclose);
    Hdf5Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    if (huge) {
      const hsize_t chunk[3] = {64, 1, 1};
      H5Pset_chunk(dcpl.get(), rank, chunk);
    }
    const Hdf5Handle str = string_type();
    Hdf5Handle set(H5Dcreate2(loc, name.c_str(), ty == Ty::str ? str.get() : file_type(ty), space.get(), H5P_DEFAULT,
                              dcpl.get(), H5P_DEFAULT),
                   H5Dclose);
    if (!set.ok()) return;  // e.g. a name given twice
    if (!huge && count > 0)
      write_values(ty, count, in, role_of(name), str.get(), [&](hid_t mem, const void* buf) {
        H5Dwrite(set.get(), mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
      });
    if (attr)
      attribute(set.get(), "stored", attr_spec, Role::integer);
    else if (stored_attribute)
      int_attribute(set.get(), "stored", 1);
  }

  // A group's datasets: `names` (bit k of the mask byte leaves names[k] out), a common length, a variant byte
  // each, then 0-3 datasets named from `extras`.
  void datasets(hid_t loc, const std::vector<std::string>& names, const std::vector<std::string>& extras,
                bool stored_attribute) {
    const std::uint8_t omit = in.front();
    const std::size_t n = (in.front() + 3u) % 33;
    for (std::size_t k = 0; k < names.size(); ++k)
      if (!(omit >> k & 1)) dataset(loc, names[k], in.front(), n, stored_attribute, names[0]);
    const int more = in.front() % 4;
    for (int k = 0; k < more; ++k) {
      const std::uint8_t which = in.front();
      const std::string& name = which & 128 ? names[which % names.size()] : extras[which % extras.size()];
      dataset(loc, name, in.front(), n, stored_attribute, names[0]);
    }
  }

  void h5part(hid_t f) {
    static const std::vector<std::string> names = {"x", "y", "vx", "vy", "mass", "phase", "fixed", "z"};
    static const std::vector<std::string> extras = {"z", "id", "rho", "Step#1", "TimeValue", "u", "X", "mass "};
    const int steps = in.front() % 5;
    std::string previous = "Step#0";
    for (int s = 0; s < steps; ++s) {
      const std::uint8_t nb = in.front();
      std::string name;
      if (nb < 200) name = "Step#" + std::to_string(nb % 50);
      else if (nb < 250) name = "Step#0" + std::to_string(nb % 10);
      else {
        static const char* odd[] = {"Step#999999999999", "Step#1234567890123456789", "Step#-1", "Step#1x",
                                    "step#3", "Step#"};
        name = odd[nb - 250];
      }
      const std::uint8_t flags = in.front();
      switch ((flags >> 2) & 3) {
        case 0: {
          Hdf5Handle g(H5Gcreate2(f, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
          if (!g.ok()) break;
          if (!(flags & 1)) {
            if (flags & 2) attribute(g.get(), "TimeValue", in.front(), Role::time);
            else scalar_attribute(g.get(), "TimeValue", value(in, Role::time, static_cast<std::size_t>(s)));
          }
          datasets(g.get(), names, extras, false);
          break;
        }
        case 1: dataset(f, name, 0, 3, false, "x"); break;
        case 2: odd_object(f, name, 1, ""); break;
        case 3: odd_object(f, name, 2, "/" + previous); break;
      }
      previous = name;
    }
  }

  void pysph(hid_t f, std::uint8_t header) {
    static const std::vector<std::string> names = {"x", "y", "u", "v", "m", "phase", "tag", "fixed"};
    static const std::vector<std::string> extras = {"rho", "h", "p", "gid", "pid", "z", "w", "arrays"};
    static const char* array_names[] = {"fluid", "solid", "wall", "boundary", "Fluid", "obstacle", "channel",
                                        "inlet", "walls_left", "boundary_2", "solid0", "tracer"};
    if (!(header & 32)) {
      const std::uint8_t flags = in.front();
      if (flags & 8) {
        dataset(f, "solver_data", 0, 2, false, "x");
      } else {
        Hdf5Handle g(H5Gcreate2(f, "solver_data", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
        if (g.ok() && !(flags & 1)) {
          if (flags & 2) attribute(g.get(), "t", in.front(), Role::time);
          else scalar_attribute(g.get(), "t", value(in, Role::time, 1));
        }
        if (g.ok() && (flags & 4)) {
          scalar_attribute(g.get(), "dt", 1e-4);
          int_attribute(g.get(), "count", 100);
        }
      }
    }
    if (header & 128) return;  // no /particles
    if (header & 64) return dataset(f, "particles", 0, 2, false, "x");
    Hdf5Handle particles(H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (!particles.ok()) return;
    const int arrays = (in.front() + 1) % 4;
    for (int k = 0; k < arrays; ++k) {
      const char* name = array_names[in.front() % (sizeof array_names / sizeof array_names[0])];
      const std::uint8_t flags = in.front();
      if (flags & 4) {
        dataset(particles.get(), name, 0, 2, false, "x");
        continue;
      }
      Hdf5Handle array(H5Gcreate2(particles.get(), name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      if (!array.ok()) continue;  // a name given twice
      if (flags & 8) {
        Hdf5Handle c(H5Gcreate2(array.get(), "constants", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      }
      if (flags & 1) continue;  // no `arrays`
      if (flags & 2) {
        dataset(array.get(), "arrays", 0, 3, false, "x");
        continue;
      }
      Hdf5Handle a(H5Gcreate2(array.get(), "arrays", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      if (a.ok()) datasets(a.get(), names, extras, flags & 16);
    }
  }
};

// Writes the file described by the input's bytes. False when it cannot be created.
bool write_file(const std::string& file, Input& in, std::uint8_t header) {
  Hdf5Handle f(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.ok()) return false;
  Writer w{in};
  if (header & 16) {
    Hdf5Handle g(H5Gcreate2(f.get(), "junk", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (g.ok()) w.dataset(g.get(), "x", 0, 2, false, "x");
  }
  const int layout = header & 3;
  if (layout == 0 || layout == 3) w.h5part(f.get());
  if (layout != 0) w.pysph(f.get(), header);
  return H5Fflush(f.get(), H5F_SCOPE_GLOBAL) >= 0;
}

// CLOSURELAB_FUZZ_VERBOSE=1 (checking what a corpus file decodes to): each call's outcome on stderr, and the
// written file is kept.
const bool verbose = std::getenv("CLOSURELAB_FUZZ_VERBOSE") != nullptr;

template <class F>
void expect_config_error(const char* what, F f) {
  try {
    f();
    if (verbose) std::fprintf(stderr, "%s: ok\n", what);
  } catch (const closurelab::ConfigError& e) {
    if (verbose) std::fprintf(stderr, "%s: ConfigError: %s\n", what, e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  // HDF5 frees its large per-file blocks (the metadata cache, ~1 MB, calloc'd at each open) beyond its free lists'
  // default limits; under ASan every open then maps and zeroes fresh pages, about 5 ms. Unlimited free lists keep
  // them for reuse.
  H5set_free_list_limits(-1, -1, -1, -1, -1, -1);
  closurelab::set_memory_limit_bytes(std::uint64_t{512} << 20);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace closurelab;
  Input in{data, 0, size};
  const std::uint8_t header = in.front();
  const std::uint8_t calls = in.front();
  static const char* extensions[] = {".h5part", ".h5", ".hdf5", ".hdf5"};
  const std::string file =
      "/tmp/closurelab_fuzz_h5_" + std::to_string(getpid()) + extensions[(header >> 2) & 3];
  if (!write_file(file, in, header)) return 0;

  expect_config_error("read_particle_snapshot(-1)", [&] { read_particle_snapshot(file, -1); });
  expect_config_error("read_particle_snapshot(0)", [&] { read_particle_snapshot(file, 0); });
  expect_config_error("read_particle_snapshot(byte)", [&] { read_particle_snapshot(file, static_cast<std::int8_t>(calls)); });
  expect_config_error("is_pysph_output", [&] { is_pysph_output(file); });
  expect_config_error("read_pysph_output", [&] { read_pysph_output(file); });
  expect_config_error("h5part_step_count", [&] { h5part_step_count(file); });
  expect_config_error("h5part_select_step(index)", [&] { h5part_select_step(file, H5PartStepBy::index, (calls & 7) - 1); });
  expect_config_error("h5part_select_step(number)", [&] { h5part_select_step(file, H5PartStepBy::number, calls % 50); });
  expect_config_error("h5part_steps", [&] {
    const std::vector<H5PartStep> steps = h5part_steps(file);
    double time = 0.1;
    for (std::size_t k = 0; k < steps.size() && k < 4; ++k) {
      if (steps[k].has_time) time = steps[k].time;
      expect_config_error(steps[k].group.c_str(), [&] { read_h5part(file, steps[k].number); });
    }
    h5part_select_step(file, H5PartStepBy::time, 0, time);
  });
  if (calls & 128) expect_config_error("read_h5part_all", [&] { read_h5part_all(file); });
  if (!verbose) std::remove(file.c_str());
  return 0;
}
