#pragma once

#include <string>
#include <vector>

#include <cstdint>

namespace mpm_lig::io {

//! A flat HDF5 file of named double arrays and double attributes: a run's checkpoint state.
//! Values are stored as 64-bit doubles, so a write followed by a read is bit-exact.
class CheckpointFile {
 public:
  enum class Mode { create, read };
  CheckpointFile(const std::string& filename, Mode mode);
  ~CheckpointFile();
  CheckpointFile(const CheckpointFile&) = delete;
  CheckpointFile& operator=(const CheckpointFile&) = delete;

  //! Store `values` as the 1-D dataset `name`.
  void write(const std::string& name, const std::vector<double>& values);
  //! Whether the dataset `name` exists.
  bool has(const std::string& name) const;
  //! The 1-D dataset `name`; throws naming the file if it is missing.
  std::vector<double> read(const std::string& name) const;
  //! A scalar attribute of the file's root group.
  void set(const std::string& name, double value);
  double get(const std::string& name) const;
  //! Whether the root group has the attribute `name`.
  bool has_attribute(const std::string& name) const;
  //! The first dataset or attribute holding a value that is not finite (NaN, inf), or "".
  std::string first_non_finite() const;
  //! Close now (flushes); throws if HDF5 reports an error.
  void close();

 private:
  std::string filename_;
  std::int64_t file_ = -1;  // hid_t: HDF5 stays out of this header
};

//! Replace `target` (an HDF5 file of step groups "step_NNNNNN" with an int64 "step" attribute)
//! by a copy of `source` without the groups of steps after `last_step`.
void copy_steps_up_to(const std::string& source, const std::string& target, long last_step);

}  // namespace mpm_lig::io
