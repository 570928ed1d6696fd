#pragma once

#include <string>
#include <vector>

namespace mpm_lig::materials {

//! Where a material saves its part of a checkpoint: named double arrays and scalars (names are
//! the material's own; the checkpoint keeps materials apart) and a folder for files of its own.
//! Every rank calls write() and set() with the same values; they are stored once.
class CheckpointWriter {
 public:
  virtual ~CheckpointWriter() = default;
  //! This material's folder inside the checkpoint; it exists on every rank.
  virtual std::string folder() const = 0;
  //! Store `values` as the array `name`.
  virtual void write(const std::string& name, const std::vector<double>& values) = 0;
  //! Store one number as `name`.
  virtual void set(const std::string& name, double value) = 0;
  //! The SHA-256 of `file` (relative to folder()), computed by the rank that wrote it: the
  //! checkpoint's manifest lists it without reading the file again.
  virtual void record_digest(const std::string& file, const std::string& sha256) = 0;
};

//! The material's part of a checkpoint read back; every lookup throws naming the checkpoint
//! and the entry when it is missing.
class CheckpointReader {
 public:
  virtual ~CheckpointReader() = default;
  //! This material's folder inside the checkpoint.
  virtual std::string folder() const = 0;
  //! Whether the array `name` was saved.
  virtual bool has(const std::string& name) const = 0;
  virtual std::vector<double> read(const std::string& name) const = 0;
  virtual double get(const std::string& name) const = 0;
  //! "checkpoint '<dir>', material <id>": for messages.
  virtual std::string describe() const = 0;
};

}  // namespace mpm_lig::materials
