#include "io/field_index.h"

#include <algorithm>
#include <utility>

#include "io/hdf5_handle.h"

namespace mpm_lig::io {
namespace {

struct Layout {
  H5T_class_t type_class = H5T_NO_CLASS;
  int rank = 0;
  hsize_t dims[2] = {0, 0};
};

Layout dataset_layout(hid_t group, const std::string& name) {
  H5Dataset dataset(check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "open dataset " + name));
  H5Type type(check(H5Dget_type(dataset.get()), "read the type of " + name));
  H5Space space(check(H5Dget_space(dataset.get()), "read the shape of " + name));
  Layout layout;
  layout.type_class = H5Tget_class(type.get());
  layout.rank = H5Sget_simple_extent_ndims(space.get());
  if (layout.rank < 1 || layout.rank > 2)
    throw std::runtime_error("HDF5: unexpected rank of " + name);
  H5Sget_simple_extent_dims(space.get(), layout.dims, nullptr);
  return layout;
}

//! The kind FieldWriter wrote a dataset as, from its type and shape.
XdmfKind kind_of(const Layout& layout, const std::string& name) {
  if (layout.type_class == H5T_INTEGER)
    return XdmfKind::integer;
  if (layout.rank == 1)
    return XdmfKind::scalar;
  if (layout.dims[1] == 3)
    return XdmfKind::vector;
  if (layout.dims[1] == 6)
    return XdmfKind::tensor;
  if (layout.dims[1] == 9)
    return XdmfKind::matrix;
  throw std::runtime_error("HDF5: dataset " + name + " is not a point field");
}

template <class T>
T read_attribute(hid_t object, const char* where, const char* name, hid_t mem_type) {
  H5Attribute attr(check(H5Aopen_by_name(object, where, name, H5P_DEFAULT, H5P_DEFAULT),
                         std::string("open attribute ") + name + " of " + where));
  T value{};
  check(H5Aread(attr.get(), mem_type, &value), std::string("read attribute ") + name);
  return value;
}

XdmfStep read_step(hid_t file, const std::string& group_name) {
  H5Group group(check(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT), "open " + group_name));
  XdmfStep step;
  step.group = group_name;
  step.time = read_attribute<double>(file, group_name.c_str(), "time", H5T_NATIVE_DOUBLE);
  step.points = dataset_layout(group.get(), "positions").dims[0];
  for (const std::string& name : member_names(group.get())) {
    if (name == "positions")
      continue;
    step.fields.push_back({name, kind_of(dataset_layout(group.get(), name), name)});
  }
  return step;
}

}  // namespace

std::vector<XdmfStep> read_field_steps(const std::string& h5_path) {
  quiet_hdf5_errors();
  H5File file(
      check(H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open '" + h5_path + "'"));
  std::vector<std::pair<long long, XdmfStep>> steps;
  for (const std::string& name : member_names(file.get())) {
    const auto number =
        read_attribute<long long>(file.get(), name.c_str(), "step", H5T_NATIVE_LLONG);
    steps.emplace_back(number, read_step(file.get(), name));
  }
  // Group names sort by step only up to 999999 steps: order by the step attribute.
  std::sort(steps.begin(), steps.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<XdmfStep> out;
  for (auto& s : steps)
    out.push_back(std::move(s.second));
  return out;
}

}  // namespace mpm_lig::io
