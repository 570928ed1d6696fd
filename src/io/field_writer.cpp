#include "io/field_writer.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/checkpoint_file.h"
#include "io/field_index.h"
#include "io/hdf5_handle.h"

namespace mpm_lig::io {

//! The HDF5 file and group of the step being written.
struct FieldWriter::Open {
  H5File file;
  H5Group group;
  XdmfStep step;
};

namespace {

void write_attribute(hid_t where, const char* name, hid_t mem_type, const void* value) {
  H5Space space(check(H5Screate(H5S_SCALAR), "create a scalar dataspace"));
  H5Attribute attr(check(H5Acreate2(where, name, mem_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         std::string("create attribute ") + name));
  check(H5Awrite(attr.get(), mem_type, value), std::string("write attribute ") + name);
}

void write_string_attribute(hid_t where, const char* name, const std::string& value) {
  H5Type type(check(H5Tcopy(H5T_C_S1), "copy the string type"));
  check(H5Tset_size(type.get(), value.size()), "size a string type");
  write_attribute(where, name, type.get(), value.c_str());
}

//! A 1D (columns == 0) or 2D (rows x columns) dataset, written whole.
void write_dataset(hid_t group, const std::string& name, hid_t file_type, hid_t mem_type,
                   const void* data, std::size_t rows, std::size_t columns,
                   const std::string& components = "") {
  const hsize_t dims[2] = {rows, columns};
  H5Space space(check(H5Screate_simple(columns ? 2 : 1, dims, nullptr), "create a dataspace"));
  H5Dataset dataset(check(H5Dcreate2(group, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                     H5P_DEFAULT, H5P_DEFAULT),
                          "create dataset " + name));
  if (rows > 0)
    check(H5Dwrite(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
          "write dataset " + name);
  if (!components.empty())
    write_string_attribute(dataset.get(), "components", components);
}

template <int D>
std::vector<double> padded_xyz(const std::vector<Eigen::Matrix<double, D, 1>>& points) {
  std::vector<double> out(3 * points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int d = 0; d < D; ++d)
      out[3 * i + d] = points[i][d];
  return out;
}

}  // namespace

FieldWriter::FieldWriter(const std::string& directory, const std::string& basename)
    : FieldWriter(directory, basename, {}) {
  std::filesystem::create_directories(directory);
  H5File file(check(H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                    "create '" + h5_path_ + "'"));
  replace_file(xdmf_path_, xdmf_text(h5_name_, steps_));
}

FieldWriter::FieldWriter(const std::string& directory, const std::string& basename,
                         std::vector<XdmfStep> steps)
    : steps_(std::move(steps)) {
  quiet_hdf5_errors();
  const std::filesystem::path dir(directory);
  h5_name_ = basename + ".h5";
  h5_path_ = (dir / h5_name_).string();
  xdmf_path_ = (dir / (basename + ".xdmf")).string();
}

std::unique_ptr<FieldWriter> FieldWriter::resume(const std::string& directory,
                                                 const std::string& basename, long last_step) {
  quiet_hdf5_errors();
  const std::filesystem::path earlier = std::filesystem::path(directory) / (basename + ".h5");
  if (!std::filesystem::exists(earlier))
    return std::make_unique<FieldWriter>(directory, basename);
  // The steps to keep are copied beside the file, checked, and only then renamed over it: a
  // failure at any point (full disk, kill) leaves the earlier file whole for the next try.
  std::vector<XdmfStep> steps;
  try {
    replace_atomically(
        earlier.string(),
        [&](const std::string& kept) {
          copy_steps_up_to(earlier.string(), kept, last_step);
          steps = read_field_steps(kept);
        },
        ".resume_tmp");
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot continue '" + earlier.string() +
                             "' (left unchanged): " + e.what());
  }
  std::unique_ptr<FieldWriter> writer(new FieldWriter(directory, basename, steps));
  replace_file(writer->xdmf_path_, xdmf_text(writer->h5_name_, writer->steps_));
  return writer;
}

FieldWriter::~FieldWriter() = default;

std::string FieldWriter::group_name(long step) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "step_%06ld", step);
  return buffer;
}

FieldWriter::Open& FieldWriter::open_step(long step, double time, std::size_t points) {
  if (open_)
    throw std::logic_error("FieldWriter: begin_step before end_step of the previous step");
  auto open = std::make_unique<Open>();
  open->step = XdmfStep{group_name(step), time, points, {}};
  open->file = H5File(
      check(H5Fopen(h5_path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open '" + h5_path_ + "'"));
  open->group = H5Group(check(
      H5Gcreate2(open->file.get(), open->step.group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      "create group " + open->step.group + " (was this step written already?)"));
  write_attribute(open->group.get(), "time", H5T_NATIVE_DOUBLE, &time);
  const long long step_ll = step;
  write_attribute(open->group.get(), "step", H5T_NATIVE_LLONG, &step_ll);
  open_ = std::move(open);
  return *open_;
}

void FieldWriter::begin_step(long step, double time, const std::vector<Vec3>& positions) {
  Open& open = open_step(step, time, positions.size());
  write_dataset(open.group.get(), "positions", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                positions.empty() ? nullptr : positions[0].data(), positions.size(), 3);
}

void FieldWriter::begin_step(long step, double time,
                             const std::vector<Eigen::Vector2d>& positions) {
  Open& open = open_step(step, time, positions.size());
  const std::vector<double> xyz = padded_xyz(positions);
  write_dataset(open.group.get(), "positions", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, xyz.data(),
                positions.size(), 3);
}

FieldWriter::Open& FieldWriter::current(const std::string& field, std::size_t count) {
  if (!open_)
    throw std::logic_error("FieldWriter: field '" + field + "' written outside a step");
  if (field.empty() || field.find('/') != std::string::npos || field == "positions")
    throw std::invalid_argument("FieldWriter: bad field name '" + field + "'");
  for (const XdmfField& known : open_->step.fields)
    if (known.name == field)
      throw std::invalid_argument("FieldWriter: field '" + field + "' written twice");
  if (count != open_->step.points) {
    throw std::invalid_argument("FieldWriter: field '" + field + "' has " + std::to_string(count) +
                                " values for " + std::to_string(open_->step.points) + " points");
  }
  return *open_;
}

void FieldWriter::write_doubles(const std::string& name, XdmfKind kind,
                                const std::vector<double>& data, std::size_t columns) {
  Open& open = *open_;
  const std::size_t rows = open.step.points;
  const char* components = kind == XdmfKind::tensor   ? "xx yy zz xy xz yz"
                           : kind == XdmfKind::matrix ? "xx xy xz yx yy yz zx zy zz"
                                                      : "";
  write_dataset(open.group.get(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data.data(), rows,
                columns, components);
  open.step.fields.push_back({name, kind});
}

void FieldWriter::add_scalar(const std::string& name, const std::vector<double>& values) {
  current(name, values.size());
  write_doubles(name, XdmfKind::scalar, values, 0);
}

void FieldWriter::add_vector(const std::string& name, const std::vector<Vec3>& values) {
  current(name, values.size());
  write_doubles(name, XdmfKind::vector, padded_xyz(values), 3);
}

void FieldWriter::add_vector(const std::string& name, const std::vector<Eigen::Vector2d>& values) {
  current(name, values.size());
  write_doubles(name, XdmfKind::vector, padded_xyz(values), 3);
}

void FieldWriter::add_tensor(const std::string& name, const std::vector<Voigt6>& values) {
  current(name, values.size());
  std::vector<double> flat;
  flat.reserve(6 * values.size());
  for (const Voigt6& v : values)
    flat.insert(flat.end(), v.begin(), v.end());
  write_doubles(name, XdmfKind::tensor, flat, 6);
}

void FieldWriter::add_tensor(const std::string& name, const std::vector<Mat3>& values) {
  std::vector<Voigt6> voigt;
  voigt.reserve(values.size());
  for (const Mat3& t : values)
    voigt.push_back(to_voigt(0.5 * (t + t.transpose())));
  add_tensor(name, voigt);
}

void FieldWriter::add_matrix(const std::string& name, const std::vector<Mat3>& values) {
  current(name, values.size());
  std::vector<double> flat;
  flat.reserve(9 * values.size());
  for (const Mat3& t : values)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        flat.push_back(t(i, j));
  write_doubles(name, XdmfKind::matrix, flat, 9);
}

void FieldWriter::add_int(const std::string& name, const std::vector<int>& values) {
  Open& open = current(name, values.size());
  write_dataset(open.group.get(), name, H5T_STD_I32LE, H5T_NATIVE_INT, values.data(), values.size(),
                0);
  open.step.fields.push_back({name, XdmfKind::integer});
}

void FieldWriter::end_step() {
  if (!open_)
    throw std::logic_error("FieldWriter: end_step without begin_step");
  std::unique_ptr<Open> open = std::move(open_);
  open->group.reset();
  if (!open->file.reset())
    throw std::runtime_error("HDF5: cannot close '" + h5_path_ + "'");
  steps_.push_back(std::move(open->step));
  replace_file(xdmf_path_, xdmf_text(h5_name_, steps_));
}

}  // namespace mpm_lig::io
