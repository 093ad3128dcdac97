#include "core/io/h5part.hpp"

#include <hdf5.h>

#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "core/base/errors.hpp"

namespace closurelab {

namespace {

std::mutex& hdf5_mutex() {
  static std::mutex m;
  return m;
}

// An HDF5 identifier closed by its own close function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void silence_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }  // errors become exceptions here

std::string step_name(int k) { return "Step#" + std::to_string(k); }

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
  out.assign(static_cast<std::size_t>(n), T{});
  if (n > 0 && H5Dread(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw ConfigError("", where + "/" + name + ": cannot read (truncated or corrupt file?)");
  return true;
}

Handle open_for_reading(const std::string& file) {
  silence_hdf5();
  if (H5Fis_hdf5(file.c_str()) <= 0)
    throw ConfigError("", "'" + file + "' is not a readable HDF5 file (missing, truncated or another format)");
  Handle f(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.ok()) throw ConfigError("", "cannot open HDF5 file '" + file + "'");
  return f;
}

int count_steps(hid_t f) {
  int k = 0;
  while (H5Lexists(f, step_name(k).c_str(), H5P_DEFAULT) > 0) ++k;
  return k;
}

ParticleSnapshot read_step(hid_t f, int k, const std::string& file) {
  const std::string where = file + ":" + step_name(k);
  Handle g(H5Gopen2(f, step_name(k).c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.ok()) throw ConfigError("", where + ": not a readable group");
  ParticleSnapshot s;
  if (H5Aexists(g.get(), "TimeValue") > 0) {
    Handle a(H5Aopen(g.get(), "TimeValue", H5P_DEFAULT), H5Aclose);
    if (!a.ok() || H5Aread(a.get(), H5T_NATIVE_DOUBLE, &s.time) < 0)
      throw ConfigError("", where + ": unreadable attribute TimeValue");
  }
  ParticleSystem& p = s.particles;
  for (auto [name, v] : {std::pair{"x", &p.x}, {"y", &p.y}, {"vx", &p.vx}, {"vy", &p.vy}, {"mass", &p.mass}})
    if (!read_dataset(g.get(), name, H5T_NATIVE_DOUBLE, *v, where))
      throw ConfigError("", where + ": no dataset '" + std::string(name) + "' (needed: x, y, vx, vy, mass)");
  if (!read_dataset(g.get(), "phase", H5T_NATIVE_INT, p.phase, where)) p.phase.assign(p.x.size(), 0);
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

int h5part_step_count(const std::string& file) {
  std::lock_guard<std::mutex> lock(hdf5_mutex());
  const Handle f = open_for_reading(file);
  return count_steps(f.get());
}

ParticleSnapshot read_h5part(const std::string& file, int step) {
  std::lock_guard<std::mutex> lock(hdf5_mutex());
  const Handle f = open_for_reading(file);
  const int n = count_steps(f.get());
  if (n == 0) throw ConfigError("", "'" + file + "' holds no H5Part step (no group Step#0)");
  if (step < -1 || step >= n)
    throw ConfigError("", "'" + file + "' has " + std::to_string(n) + " steps; step " + std::to_string(step) +
                              " does not exist (0.." + std::to_string(n - 1) + ", or -1 for the last)");
  return read_step(f.get(), step < 0 ? n - 1 : step, file);
}

std::vector<ParticleSnapshot> read_h5part_all(const std::string& file) {
  std::lock_guard<std::mutex> lock(hdf5_mutex());
  const Handle f = open_for_reading(file);
  std::vector<ParticleSnapshot> out;
  const int n = count_steps(f.get());
  for (int k = 0; k < n; ++k) out.push_back(read_step(f.get(), k, file));
  return out;
}

}  // namespace closurelab
