#include "io/checkpoint_file.h"

#include <cmath>
#include <stdexcept>

#include "io/hdf5_handle.h"

namespace mpm_lig::io {

CheckpointFile::CheckpointFile(const std::string& filename, Mode mode) : filename_(filename) {
  quiet_hdf5_errors();
  file_ = check(mode == Mode::create
                    ? H5Fcreate(filename.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)
                    : H5Fopen(filename.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                "open '" + filename + "'");
}

CheckpointFile::~CheckpointFile() {
  if (file_ >= 0)
    H5Fclose(file_);
}

void CheckpointFile::write(const std::string& name, const std::vector<double>& values) {
  const hsize_t size = values.size();
  H5Space space(check(H5Screate_simple(1, &size, nullptr), "create a dataspace"));
  H5Dataset set(check(H5Dcreate2(file_, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                 H5P_DEFAULT, H5P_DEFAULT),
                      "create '" + name + "' in '" + filename_ + "'"));
  if (size > 0 &&
      H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw std::runtime_error("HDF5: cannot write '" + name + "' in '" + filename_ + "'");
}

bool CheckpointFile::has(const std::string& name) const {
  return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<double> CheckpointFile::read(const std::string& name) const {
  H5Dataset set(check(H5Dopen2(file_, name.c_str(), H5P_DEFAULT),
                      "find '" + name + "' in '" + filename_ + "'"));
  H5Space space(check(H5Dget_space(set.get()), "read the shape of '" + name + "'"));
  const hssize_t size = H5Sget_simple_extent_npoints(space.get());
  std::vector<double> values(static_cast<std::size_t>(size));
  if (size > 0 &&
      H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw std::runtime_error("HDF5: cannot read '" + name + "' in '" + filename_ + "'");
  return values;
}

void CheckpointFile::set(const std::string& name, double value) {
  H5Space space(check(H5Screate(H5S_SCALAR), "create a dataspace"));
  H5Attribute a(
      check(H5Acreate2(file_, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
            "create attribute '" + name + "'"));
  if (H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    throw std::runtime_error("HDF5: cannot write attribute '" + name + "'");
}

double CheckpointFile::get(const std::string& name) const {
  H5Attribute a(check(H5Aopen(file_, name.c_str(), H5P_DEFAULT),
                      "find attribute '" + name + "' in '" + filename_ + "'"));
  double value = 0.0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    throw std::runtime_error("HDF5: cannot read attribute '" + name + "'");
  return value;
}

bool CheckpointFile::has_attribute(const std::string& name) const {
  return H5Aexists(file_, name.c_str()) > 0;
}

void CheckpointFile::close() {
  const herr_t status = H5Fclose(file_);
  file_ = -1;
  if (status < 0)
    throw std::runtime_error("HDF5: cannot close '" + filename_ + "'");
}

namespace {

//! Names of the datasets or of the attributes of the root group of `file`.
std::vector<std::string> member_names(hid_t file, bool attributes) {
  std::vector<std::string> names;
  if (attributes) {
    H5Aiterate2(
        file, H5_INDEX_NAME, H5_ITER_INC, nullptr,
        [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
          static_cast<std::vector<std::string>*>(out)->push_back(name);
          return 0;
        },
        &names);
  } else {
    H5Literate(
        file, H5_INDEX_NAME, H5_ITER_INC, nullptr,
        [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
          static_cast<std::vector<std::string>*>(out)->push_back(name);
          return 0;
        },
        &names);
  }
  return names;
}

bool all_finite(const std::vector<double>& values) {
  for (const double v : values) {
    if (!std::isfinite(v))
      return false;
  }
  return true;
}

}  // namespace

std::string CheckpointFile::first_non_finite() const {
  for (const std::string& name : member_names(file_, false)) {
    if (!all_finite(read(name)))
      return name;
  }
  for (const std::string& name : member_names(file_, true)) {
    if (!std::isfinite(get(name)))
      return name;
  }
  return "";
}

void copy_steps_up_to(const std::string& source, const std::string& target, long last_step) {
  quiet_hdf5_errors();
  H5File in(check(H5Fopen(source.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open '" + source + "'"));
  H5File out(check(H5Fcreate(target.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                   "create '" + target + "'"));
  for (const std::string& name : member_names(in.get())) {
    H5Attribute a(check(H5Aopen_by_name(in.get(), name.c_str(), "step", H5P_DEFAULT, H5P_DEFAULT),
                        "read the step of '" + name + "'"));
    long long step = 0;
    H5Aread(a.get(), H5T_NATIVE_LLONG, &step);
    if (step <= last_step)
      check(H5Ocopy(in.get(), name.c_str(), out.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
            "copy '" + name + "'");
  }
  if (!out.reset())
    throw std::runtime_error("HDF5: cannot close '" + target + "'");
}

}  // namespace mpm_lig::io
