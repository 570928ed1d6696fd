#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/case_node.h"
#include "core/tensor.h"

namespace mpm_lig::element {

class StrainPath;

//! A recorded deformation history to replay on one RVE (element test "recorded_path",
//! docs/methods.md §6): the deformation gradient F(t_k) of every recorded row. The RVE starts
//! from its packing at the first row; each interval k (rows k → k+1) is one increment.
struct RecordedPath {
  std::string source;              //!< the file it came from
  long point = -1;                 //!< the material point of a results.h5 path; -1 for a CSV
  std::vector<std::string> label;  //!< per row, for messages: "row 3 (line 4)", "step_000012"
  std::vector<double> time;        //!< per row: the recorded time
  std::vector<Mat3> F;             //!< per row: the deformation gradient
  //! Per interval: the increment the recording run itself applied, where the file holds it
  //! and the interval is one MPM step (results.h5 with output.deformation_gradient, written
  //! every step): replayed as these bits instead of F_{k+1} F_k^-1.
  std::vector<std::optional<Mat3>> recorded_increment;
  //! Per interval: DEM steps to run (CSV column `substeps`, or the recording run's own with
  //! results.h5 and "substeps": "recorded"); 0: the RVE's sub-stepping rule.
  std::vector<int> substeps;
  //! Per row: the mean stress [Pa, compression positive; in-plane for a 2D RVE] to hold the RVE
  //! at (CSV column `p`); used with "volume": "free", where the RVE takes only the isochoric
  //! part of each increment and its volume follows this stress instead of det F.
  std::vector<double> mean_stress;
  bool free_volume = false;           //!< "volume": "free"
  double pressure_tolerance = 0.005;  //!< free volume: relative tolerance of the mean stress

  std::size_t intervals() const { return F.empty() ? 0 : F.size() - 1; }
  //! The increment of interval k: the recorded one, or F_{k+1} F_k^-1.
  Mat3 increment(std::size_t k) const;
};

//! ΔF with ΔF·from = to, by an LU solve: for diagonal F each component is the correctly rounded
//! quotient; when both are plane (2D) deformations the out-of-plane part is exactly identity.
Mat3 increment_between(const Mat3& from, const Mat3& to);

//! Reads and checks `analysis.path` for an RVE of `dimension`: {"csv": FILE, "volume":
//! "recorded" | "free"} or {"results": FILE, "point": i, "substeps": "rule" | "recorded"}.
//! "free" needs the CSV's column p, finite and > 0 on every row. Every row must have a finite F
//! with det F > 0 (a 2D RVE: plane F) and its time must exceed the previous row's; a problem is a
//! CaseError at the key that named the file, with the row (CSV) or step group (results.h5).
std::shared_ptr<const RecordedPath> read_recorded_path(const CaseNode& path, int dimension);

//! The strain path of a recorded history; with a free volume, a servo holds the RVE's mean
//! stress at the recorded one within the path's `pressure_tolerance` (relative) by isotropic
//! corrections, from a first stiffness estimate `stiffness` [Pa per unit per-axis strain], for
//! an RVE of `dimension`.
std::unique_ptr<StrainPath> make_recorded_strain_path(std::shared_ptr<const RecordedPath> path,
                                                      int dimension, double stiffness);

}  // namespace mpm_lig::element
