#include "coupling/cost_record.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "io/hdf5_handle.h"

namespace mpm_lig::coupling {
namespace {

using io::check;

//! Rows per chunk: about 256 KB of one per-point field, at least one row.
hsize_t chunk_rows(std::size_t points) {
  return static_cast<hsize_t>(
      std::clamp<std::size_t>(65536 / std::max<std::size_t>(points, 1), 1, 1024));
}

void create_set(hid_t file, const char* name, hid_t type, std::size_t points) {
  const int rank = points > 0 ? 2 : 1;
  const hsize_t dims[2] = {0, points};
  const hsize_t max[2] = {H5S_UNLIMITED, points};
  const hsize_t chunk[2] = {chunk_rows(std::max<std::size_t>(points, 1)),
                            std::max<hsize_t>(points, 1)};
  io::H5Space space(check(H5Screate_simple(rank, dims, max), "create a dataspace"));
  io::Hdf5Handle<H5Pclose> props(check(H5Pcreate(H5P_DATASET_CREATE), "create properties"));
  check(H5Pset_chunk(props.get(), rank, chunk), "set a chunk size");
  check(H5Pset_shuffle(props.get()), "set the shuffle filter");
  check(H5Pset_deflate(props.get(), 4), "set compression");
  io::H5Dataset set(
      check(H5Dcreate2(file, name, type, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT),
            std::string("create '") + name + "'"));
}

void set_attribute(hid_t file, const char* name, double value) {
  io::H5Space space(check(H5Screate(H5S_SCALAR), "create a dataspace"));
  io::H5Attribute a(
      check(H5Acreate2(file, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), name));
  check(H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value), std::string("write ") + name);
}

//! Rows of dataset `name` (its first dimension).
hsize_t rows_of(hid_t set) {
  io::H5Space space(check(H5Dget_space(set), "read a shape"));
  hsize_t dims[2] = {0, 0};
  check(H5Sget_simple_extent_dims(space.get(), dims, nullptr), "read a shape");
  return dims[0];
}

//! Append `rows` rows of `width` values (0: a 1-D dataset) to dataset `name`.
template <class T>
void append(hid_t file, const char* name, hid_t mem_type, const std::vector<T>& values,
            std::size_t rows, std::size_t width) {
  io::H5Dataset set(check(H5Dopen2(file, name, H5P_DEFAULT), std::string("open '") + name + "'"));
  const hsize_t start_row = rows_of(set.get());
  const int rank = width > 0 ? 2 : 1;
  const hsize_t new_dims[2] = {start_row + rows, width};
  check(H5Dset_extent(set.get(), new_dims), std::string("extend '") + name + "'");
  io::H5Space file_space(check(H5Dget_space(set.get()), "read a shape"));
  const hsize_t start[2] = {start_row, 0};
  const hsize_t count[2] = {rows, width};
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
        "select rows");
  io::H5Space memory(check(H5Screate_simple(rank, count, nullptr), "create a dataspace"));
  check(H5Dwrite(set.get(), mem_type, memory.get(), file_space.get(), H5P_DEFAULT, values.data()),
        std::string("write '") + name + "'");
}

constexpr const char* kPerPoint[] = {"predicted_steps", "measured_steps", "seconds", "group"};

//! Keep the rows of `file` whose update is at most `last`; throws when it is not a record.
void cut_rows(const std::string& file, long last) {
  io::H5File f(check(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open '" + file + "'"));
  io::H5Dataset updates(check(H5Dopen2(f.get(), "update", H5P_DEFAULT), "open 'update'"));
  const hsize_t rows = rows_of(updates.get());
  std::vector<long long> u(rows);
  if (rows > 0)
    check(H5Dread(updates.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, u.data()),
          "read 'update'");
  hsize_t keep = 0;
  while (keep < rows && u[keep] <= last)
    ++keep;
  const hsize_t one[1] = {keep};
  check(H5Dset_extent(updates.get(), one), "cut 'update'");
  io::H5Dataset groups(check(H5Dopen2(f.get(), "groups", H5P_DEFAULT), "open 'groups'"));
  check(H5Dset_extent(groups.get(), one), "cut 'groups'");
  for (const char* name : kPerPoint) {
    io::H5Dataset set(check(H5Dopen2(f.get(), name, H5P_DEFAULT), name));
    io::H5Space space(check(H5Dget_space(set.get()), "read a shape"));
    hsize_t dims[2] = {0, 0};
    check(H5Sget_simple_extent_dims(space.get(), dims, nullptr), "read a shape");
    dims[0] = keep;
    check(H5Dset_extent(set.get(), dims), std::string("cut '") + name + "'");
  }
}

}  // namespace

CostRecord::CostRecord(std::string file, std::size_t points, double grains,
                       double update_cost_steps, double floor_steps)
    : file_(std::move(file)),
      points_(points),
      grains_(grains),
      update_cost_steps_(update_cost_steps),
      floor_steps_(floor_steps) {}

CostRecord::~CostRecord() {
  try {
    flush();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: the cost record '%s' misses its last rows: %s\n", file_.c_str(),
                 e.what());
  }
}

void CostRecord::create() {
  io::H5File f(check(H5Fcreate(file_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                     "create '" + file_ + "'"));
  create_set(f.get(), "update", H5T_STD_I64LE, 0);
  create_set(f.get(), "groups", H5T_STD_I32LE, 0);
  create_set(f.get(), "predicted_steps", H5T_STD_I32LE, points_);
  create_set(f.get(), "measured_steps", H5T_STD_I32LE, points_);
  create_set(f.get(), "seconds", H5T_IEEE_F32LE, points_);
  create_set(f.get(), "group", H5T_STD_I32LE, points_);
  set_attribute(f.get(), "grains", grains_);
  set_attribute(f.get(), "update_cost_steps", update_cost_steps_);
  set_attribute(f.get(), "floor_steps", floor_steps_);
  set_attribute(f.get(), "points", static_cast<double>(points_));
}

void CostRecord::clear_rows() {
  update_.clear();
  groups_.clear();
  predicted_.clear();
  measured_.clear();
  seconds_.clear();
  group_.clear();
}

void CostRecord::continue_after(long update) {
  clear_rows();
  try {
    H5E_BEGIN_TRY {
      cut_rows(file_, update);
    }
    H5E_END_TRY;
  } catch (const std::exception&) {
    create();
  }
}

void CostRecord::add(long update, int groups, const std::vector<double>& predicted_steps,
                     const std::vector<double>& measured_steps, const std::vector<double>& seconds,
                     const std::vector<int>& group) {
  update_.push_back(update);
  groups_.push_back(groups);
  for (std::size_t p = 0; p < points_; ++p) {
    predicted_.push_back(static_cast<int>(std::lround(predicted_steps[p])));
    measured_.push_back(static_cast<int>(std::lround(measured_steps[p])));
    seconds_.push_back(static_cast<float>(seconds[p]));
    group_.push_back(group[p]);
  }
}

void CostRecord::flush() {
  const std::size_t rows = update_.size();
  if (rows == 0)
    return;
  try {
    io::H5File f(check(H5Fopen(file_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open"));
    append(f.get(), "update", H5T_NATIVE_LLONG, update_, rows, 0);
    append(f.get(), "groups", H5T_NATIVE_INT, groups_, rows, 0);
    append(f.get(), "predicted_steps", H5T_NATIVE_INT, predicted_, rows, points_);
    append(f.get(), "measured_steps", H5T_NATIVE_INT, measured_, rows, points_);
    append(f.get(), "seconds", H5T_NATIVE_FLOAT, seconds_, rows, points_);
    append(f.get(), "group", H5T_NATIVE_INT, group_, rows, points_);
    if (!f.reset())
      throw std::runtime_error("HDF5: cannot close");
  } catch (const std::exception& e) {
    throw std::runtime_error("cost record '" + file_ + "': " + e.what());
  }
  clear_rows();
}

}  // namespace mpm_lig::coupling
