#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/tensor.h"
#include "io/xdmf_index.h"

namespace mpm_lig::io {

//! Point fields over time: `DIR/<basename>.h5` with one group per output step, and
//! `DIR/<basename>.xdmf`, a temporal collection of Polyvertex grids that ParaView opens.
//!
//! Layout of the HDF5 file (all floating point data as 64-bit doubles):
//!
//!     /step_000120            attributes: time (double), step (int64)
//!         positions           n x 3 (z = 0 in 2D)
//!         <scalar>            n
//!         <vector>            n x 3 (z = 0 in 2D)
//!         <tensor>            n x 6 Voigt xx yy zz xy xz yz (attribute "components")
//!         <matrix>            n x 9 row-major xx xy xz yx yy yz zx zy zz (attribute "components")
//!         <int field>         n, 32-bit integers (material ids, ...)
//!
//! The HDF5 file is opened for one step only and closed at `end_step`, and the XDMF file is
//! replaced atomically after it: a run killed between steps leaves both complete and readable.
//! Serial: with MPI, one rank writes what all ranks gathered.
class FieldWriter {
 public:
  //! Creates `directory` if needed and starts an empty `<basename>.h5` (an older one is replaced).
  FieldWriter(const std::string& directory, const std::string& basename = "results");
  //! Continue the fields of an earlier run in `directory`: its steps up to `last_step` are
  //! kept (later ones dropped) and stay in the XDMF index with the new ones. Without an
  //! earlier file, starts one. A failure leaves the earlier file as it was.
  static std::unique_ptr<FieldWriter> resume(const std::string& directory,
                                             const std::string& basename, long last_step);
  ~FieldWriter();
  FieldWriter(const FieldWriter&) = delete;
  FieldWriter& operator=(const FieldWriter&) = delete;

  //! Start output step `step` at `time` for points at `positions`; sets the point count.
  void begin_step(long step, double time, const std::vector<Vec3>& positions);
  //! Same, for 2D positions (written with z = 0).
  void begin_step(long step, double time, const std::vector<Eigen::Vector2d>& positions);

  //! One value per point.
  void add_scalar(const std::string& name, const std::vector<double>& values);
  //! One vector per point.
  void add_vector(const std::string& name, const std::vector<Vec3>& values);
  //! One 2D vector per point (written with z = 0).
  void add_vector(const std::string& name, const std::vector<Eigen::Vector2d>& values);
  //! One symmetric tensor per point, Voigt order xx yy zz xy xz yz.
  void add_tensor(const std::string& name, const std::vector<Voigt6>& values);
  //! One symmetric tensor per point (its symmetric part is written).
  void add_tensor(const std::string& name, const std::vector<Mat3>& values);
  //! One general (non-symmetric) 3 x 3 tensor per point, row-major: exact, so that a
  //! deformation gradient read back is the one the run used.
  void add_matrix(const std::string& name, const std::vector<Mat3>& values);
  //! One integer per point (material id, body id, ...).
  void add_int(const std::string& name, const std::vector<int>& values);

  //! Close the step: the HDF5 file is closed (so flushed) and the XDMF file rewritten.
  void end_step();

  //! Number of steps completed by `end_step`.
  std::size_t steps_written() const { return steps_.size(); }

  //! HDF5 group name of an output step ("step_000120").
  static std::string group_name(long step);

 private:
  //! Continue `<basename>.h5` in `directory`, which holds `steps`.
  FieldWriter(const std::string& directory, const std::string& basename,
              std::vector<XdmfStep> steps);
  struct Open;
  Open& open_step(long step, double time, std::size_t points);
  Open& current(const std::string& field, std::size_t count);
  void write_doubles(const std::string& name, XdmfKind kind, const std::vector<double>& data,
                     std::size_t columns);

  std::string h5_path_;
  std::string h5_name_;  // as the XDMF refers to it: relative, so the folder can move
  std::string xdmf_path_;
  std::vector<XdmfStep> steps_;
  std::unique_ptr<Open> open_;  // the step being written, between begin_step and end_step
};

}  // namespace mpm_lig::io
