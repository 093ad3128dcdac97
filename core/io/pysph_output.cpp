#include "core/io/pysph_output.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/io/hdf5_handle.hpp"

namespace closurelab {

namespace {

// Calls into libhdf5 from this file hold one mutex. (Debian's libhdf5 is built thread-safe,
// H5is_library_threadsafe = 1, so this reader and the H5Part one, which holds its own, may run at once.)
std::mutex& pysph_hdf5_mutex() {
  static std::mutex m;
  return m;
}

using Handle = detail::Hdf5Handle;

bool has_link(hid_t loc, const char* name) { return H5Lexists(loc, name, H5P_DEFAULT) > 0; }

bool is_pysph_file(hid_t f) {
  if (!has_link(f, "particles") || !has_link(f, "solver_data")) return false;
  H5O_info_t info;
  return H5Oget_info_by_name(f, "particles", &info, H5P_DEFAULT) >= 0 && info.type == H5O_TYPE_GROUP;
}

std::vector<std::string> child_names(hid_t group) {
  std::vector<std::string> names;
  H5Literate(
      group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->push_back(name);
        return 0;
      },
      &names);
  return names;
}

// Property `name` of an array group as `mem_type`; false when it is absent or not stored (PySPH writes an empty
// dataset with the attribute stored = false for a property it did not output).
template <class T>
bool read_property(hid_t arrays, const std::string& name, hid_t mem_type, std::vector<T>& out,
                   const std::string& where) {
  if (!has_link(arrays, name.c_str())) return false;
  Handle set(H5Dopen2(arrays, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.ok()) throw ConfigError("", where + "/" + name + ": not a readable dataset");
  if (H5Aexists(set.get(), "stored") > 0) {
    Handle a(H5Aopen(set.get(), "stored", H5P_DEFAULT), H5Aclose);
    std::int64_t stored = 1;
    if (a.ok() && detail::holds_one_value(a.get()) && H5Aread(a.get(), H5T_NATIVE_INT64, &stored) >= 0 && stored == 0)
      return false;
  }
  Handle space(H5Dget_space(set.get()), H5Sclose);
  if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 1)
    throw ConfigError("", where + "/" + name + ": not a one-dimensional dataset");
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  // A chunked dataset may declare 2^45 values in a file of a few kB (a bare std::bad_alloc): bounded first, as
  // the H5Part reader does.
  check_allocation(static_cast<double>(n), static_cast<double>(sizeof(T)),
                   where + "/" + name + ": " + std::to_string(n) + " values");
  out.assign(static_cast<std::size_t>(n), T{});
  if (n > 0 && H5Dread(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw ConfigError("", where + "/" + name + ": cannot read (truncated or corrupt file?)");
  return true;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// PySPH's usual names for particle arrays that do not move.
bool wall_array_name(const std::string& name) {
  const std::string n = lower(name);
  for (const char* w : {"solid", "wall", "walls", "boundary", "obstacle", "channel"})
    if (n == w) return true;
  for (const char* prefix : {"solid", "wall", "boundary"})
    if (n.rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace

bool is_pysph_output(const std::string& file) {
  std::lock_guard<std::mutex> lock(pysph_hdf5_mutex());
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (H5Fis_hdf5(file.c_str()) <= 0) return false;
  Handle f(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  return f.ok() && is_pysph_file(f.get());
}

ParticleSnapshot read_pysph_output(const std::string& file) {
  std::lock_guard<std::mutex> lock(pysph_hdf5_mutex());
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (H5Fis_hdf5(file.c_str()) <= 0)
    throw ConfigError("", "'" + file + "' is not a readable HDF5 file (missing, truncated or another format)");
  Handle f(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.ok()) throw ConfigError("", "cannot open HDF5 file '" + file + "'");
  if (!is_pysph_file(f.get()))
    throw ConfigError("", "'" + file + "' is not PySPH output (no groups /particles and /solver_data)");
  ParticleSnapshot s;
  {
    Handle solver(H5Gopen2(f.get(), "solver_data", H5P_DEFAULT), H5Gclose);
    if (solver.ok() && H5Aexists(solver.get(), "t") > 0) {
      Handle a(H5Aopen(solver.get(), "t", H5P_DEFAULT), H5Aclose);
      if (a.ok() && !detail::holds_one_value(a.get()))
        throw ConfigError("", file + ":/solver_data: attribute t is not a single value");
      if (!a.ok() || H5Aread(a.get(), H5T_NATIVE_DOUBLE, &s.time) < 0)
        throw ConfigError("", file + ":/solver_data: unreadable attribute t");
    }
  }
  Handle particles(H5Gopen2(f.get(), "particles", H5P_DEFAULT), H5Gclose);
  const std::vector<std::string> names = child_names(particles.get());
  if (names.empty()) throw ConfigError("", "'" + file + "' holds no PySPH particle array (/particles is empty)");
  ParticleSystem& p = s.particles;
  for (const std::string& name : names) {
    const std::string where = file + ":/particles/" + name + "/arrays";
    Handle arrays(H5Gopen2(particles.get(), (name + "/arrays").c_str(), H5P_DEFAULT), H5Gclose);
    if (!arrays.ok()) throw ConfigError("", where + ": no group 'arrays'");
    std::vector<double> x, y, u, v, m, fixed;
    std::vector<int> phase, tag;
    for (auto [prop, vec] : {std::pair{"x", &x}, {"y", &y}, {"u", &u}, {"v", &v}, {"m", &m}})
      if (!read_property(arrays.get(), prop, H5T_NATIVE_DOUBLE, *vec, where))
        throw ConfigError("", where + ": no stored property '" + std::string(prop) + "' (needed: x, y, u, v, m)");
    const std::size_t n = x.size();
    const auto check_length = [&](std::size_t len, const char* prop) {
      if (len != n)
        throw ConfigError("", where + "/" + prop + ": " + std::to_string(len) + " values, x has " + std::to_string(n));
    };
    check_length(y.size(), "y");
    check_length(u.size(), "u");
    check_length(v.size(), "v");
    check_length(m.size(), "m");
    const bool has_phase = read_property(arrays.get(), "phase", H5T_NATIVE_INT, phase, where);
    if (has_phase) check_length(phase.size(), "phase");
    const bool has_tag = read_property(arrays.get(), "tag", H5T_NATIVE_INT, tag, where);
    if (has_tag) check_length(tag.size(), "tag");
    const bool has_fixed_prop = read_property(arrays.get(), "fixed", H5T_NATIVE_DOUBLE, fixed, where);
    if (has_fixed_prop) check_length(fixed.size(), "fixed");
    const bool wall = wall_array_name(name);
    s.has_fixed = s.has_fixed || has_fixed_prop || wall;
    for (std::size_t a = 0; a < n; ++a) {
      if (has_tag && tag[a] != 0) continue;  // a remote or ghost copy
      p.add(x[a], y[a], m[a], has_phase ? phase[a] : 0, has_fixed_prop ? fixed[a] != 0 : wall);
      p.vx.back() = u[a];
      p.vy.back() = v[a];
    }
  }
  check_particles(p, file);
  return s;
}

std::string pysph_npz_refusal(const std::string& file) {
  return "'" + file +
         "' is PySPH's .npz output, whose metadata are pickled Python objects; closurelab reads PySPH's .hdf5 "
         "output (PySPH writes it when h5py is installed, or convert: python3 -c \"import sys; "
         "from pysph.solver.utils import load, dump; d = load(sys.argv[1]); "
         "dump(sys.argv[1][:-4] + '.hdf5', list(d['arrays'].values()), d['solver_data'])\" " +
         file + ")";
}

}  // namespace closurelab
