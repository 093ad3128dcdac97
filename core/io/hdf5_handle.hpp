#pragma once
// An HDF5 identifier closed by its own close function when it goes out of scope, shared by the two HDF5 readers
// (h5part.cpp, pysph_output.cpp). Private to closurelab_core: it includes <hdf5.h>, so it is not installed
// (cmake/install.cmake) and no installed header includes it.
#include <hdf5.h>

#include <utility>

namespace closurelab::detail {

class Hdf5Handle {
 public:
  Hdf5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Hdf5Handle(Hdf5Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(Hdf5Handle&&) = delete;
  ~Hdf5Handle() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// True when the attribute `attr` holds exactly one value. H5Aread writes all of an attribute's values, so an array
// attribute (TimeValue, t or stored of shape [3], as fuzz_hdf5_snapshot wrote them) read into one variable overran it.
inline bool holds_one_value(hid_t attr) {
  Hdf5Handle space(H5Aget_space(attr), H5Sclose);
  return space.ok() && H5Sget_simple_extent_npoints(space.get()) == 1;
}

}  // namespace closurelab::detail
