#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <hdf5.h>

namespace mpm_lig::io {

//! Owns one HDF5 identifier and closes it with the matching H5?close on destruction.
//!
//! Every HDF5 call of the field writer goes through `check`, so that a failure is an
//! exception naming what was being done instead of a negative id used later.
template <herr_t (*Close)(hid_t)>
class Hdf5Handle {
 public:
  Hdf5Handle() = default;
  explicit Hdf5Handle(hid_t id) : id_(id) {}
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  Hdf5Handle(Hdf5Handle&& other) noexcept : id_(other.release()) {}
  Hdf5Handle& operator=(Hdf5Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = other.release();
    }
    return *this;
  }
  ~Hdf5Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  hid_t release() {
    const hid_t id = id_;
    id_ = -1;
    return id;
  }
  //! Close now; returns false if HDF5 reported an error while closing (for example on flush).
  bool reset() {
    const bool ok = id_ < 0 || Close(id_) >= 0;
    id_ = -1;
    return ok;
  }

 private:
  hid_t id_ = -1;
};

using H5File = Hdf5Handle<H5Fclose>;
using H5Group = Hdf5Handle<H5Gclose>;
using H5Dataset = Hdf5Handle<H5Dclose>;
using H5Space = Hdf5Handle<H5Sclose>;
using H5Attribute = Hdf5Handle<H5Aclose>;
using H5Type = Hdf5Handle<H5Tclose>;

//! Throws std::runtime_error("HDF5: <what>") when `id` is negative; returns it otherwise.
//! Silence HDF5's own error printing (its HDF5-DIAG stacks), once per process: every failure
//! surfaces as an exception from `check` with a message of ours, the last thing printed.
inline void quiet_hdf5_errors() {
  static const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

inline hid_t check(hid_t id, const std::string& what) {
  if (id < 0)
    throw std::runtime_error("HDF5: cannot " + what);
  return id;
}

//! Names of the links (datasets, groups) directly in `group`, in name order.
inline std::vector<std::string> member_names(hid_t group) {
  H5G_info_t info;
  check(H5Gget_info(group, &info), "list a group");
  std::vector<std::string> names;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t length =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    check(length, "read a link name");
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(length));
    names.push_back(std::move(name));
  }
  return names;
}

}  // namespace mpm_lig::io
