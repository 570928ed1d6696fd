#include "io/point_history.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

#include "io/hdf5_handle.h"

namespace mpm_lig::io {
namespace {

template <class T>
T read_attribute(hid_t group, const char* name, hid_t mem_type, const std::string& where) {
  if (H5Aexists(group, name) <= 0)
    throw PointHistoryError(where + " has no attribute '" + name + "'");
  H5Attribute attr(check(H5Aopen(group, name, H5P_DEFAULT), std::string("open ") + name));
  T value{};
  check(H5Aread(attr.get(), mem_type, &value), std::string("read ") + name);
  return value;
}

//! Rows of dataset `name` of `group`, or -1 if the group has no such dataset.
long long dataset_rows(hid_t group, const std::string& name) {
  if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0)
    return -1;
  H5Dataset dataset(check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "open " + name));
  H5Space space(check(H5Dget_space(dataset.get()), "read the shape of " + name));
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 1 || rank > 2)
    return -1;
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  return static_cast<long long>(dims[0]);
}

//! Row `point` of dataset `name` (1 value for a 1-D dataset, its columns for a 2-D one).
std::vector<double> read_row(hid_t group, const std::string& name, std::size_t point) {
  H5Dataset dataset(check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "open " + name));
  H5Space space(check(H5Dget_space(dataset.get()), "read the shape of " + name));
  hsize_t dims[2] = {0, 1};
  const int rank = H5Sget_simple_extent_ndims(space.get());
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  const hsize_t columns = rank == 2 ? dims[1] : 1;
  const hsize_t start[2] = {point, 0}, count[2] = {1, columns};
  check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
        "select a row of " + name);
  H5Space memory(check(H5Screate_simple(rank, count, nullptr), "create a row dataspace"));
  std::vector<double> row(columns);
  check(
      H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, memory.get(), space.get(), H5P_DEFAULT, row.data()),
      "read " + name);
  return row;
}

}  // namespace

PointHistory read_point_history(const std::string& h5_path, std::size_t point,
                                const std::vector<std::string>& required,
                                const std::vector<std::string>& optional) {
  quiet_hdf5_errors();
  const std::string file_name = "'" + h5_path + "'";
  if (!std::filesystem::is_regular_file(h5_path))
    throw PointHistoryError("no such file " + file_name);
  if (H5Fis_hdf5(h5_path.c_str()) <= 0)
    throw PointHistoryError(file_name + " is not an HDF5 file");
  PointHistory h;
  try {
    H5File file(check(H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open it"));
    const std::vector<std::string> groups = member_names(file.get());
    if (groups.empty())
      throw PointHistoryError(file_name + " holds no output step");
    std::vector<long> steps;
    for (const std::string& name : groups) {
      H5Group g(check(H5Gopen2(file.get(), name.c_str(), H5P_DEFAULT), "open " + name));
      steps.push_back(static_cast<long>(
          read_attribute<long long>(g.get(), "step", H5T_NATIVE_LLONG, file_name + " " + name)));
    }
    // Group names sort by step only up to 999999 steps: order by the step attribute.
    std::vector<std::size_t> order(groups.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return steps[a] < steps[b]; });
    for (const std::size_t k : order) {
      const std::string where = file_name + " " + groups[k];
      H5Group g(check(H5Gopen2(file.get(), groups[k].c_str(), H5P_DEFAULT), "open " + groups[k]));
      const long long n = dataset_rows(g.get(), "positions");
      if (n < 0)
        throw PointHistoryError(where + " has no dataset 'positions'");
      if (h.group.empty())
        h.points = static_cast<std::size_t>(n);
      else if (static_cast<std::size_t>(n) != h.points)
        throw PointHistoryError(where + " holds " + std::to_string(n) + " points, " +
                                h.group.front() + " " + std::to_string(h.points));
      if (point >= h.points)
        throw UnknownPointError(file_name + " holds " + std::to_string(h.points) +
                                " points (0 ... " + std::to_string(h.points - 1) + ")");
      h.group.push_back(groups[k]);
      h.step.push_back(steps[k]);
      h.time.push_back(read_attribute<double>(g.get(), "time", H5T_NATIVE_DOUBLE, where));
      for (const auto* names : {&required, &optional}) {
        for (const std::string& name : *names) {
          const long long rows = dataset_rows(g.get(), name);
          if (rows < 0 && names == &required)
            throw PointHistoryError(where + " has no dataset '" + name + "'");
          if (rows >= 0 && static_cast<std::size_t>(rows) != h.points)
            throw PointHistoryError(where + ": dataset '" + name + "' has " + std::to_string(rows) +
                                    " rows for " + std::to_string(h.points) + " points");
          h.rows[name].push_back(rows < 0 ? std::vector<double>{} : read_row(g.get(), name, point));
        }
      }
    }
  } catch (const PointHistoryError&) {
    throw;
  } catch (const std::exception& e) {
    // HDF5 failures (a truncated or damaged file) come as runtime_error("HDF5: cannot ...").
    throw PointHistoryError(file_name + " cannot be read (" + e.what() + ")");
  }
  return h;
}

}  // namespace mpm_lig::io
