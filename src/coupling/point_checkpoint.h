#pragma once

#include <cstddef>
#include <vector>

#include "core/tensor.h"
#include "coupling/dem_work.h"
#include "coupling/quiet_points.h"
#include "coupling/steady_flow.h"
#include "materials/checkpoint_io.h"
#include "rve/rve.h"

namespace mpm_lig::coupling {

//! What a checkpoint keeps of one DEM point besides its engine restart file.
//!
//! Stored as one named array per field (point by point), so that a checkpoint written with
//! other fields is refused by name. A new field is a member here and a line in the table of
//! point_checkpoint.cpp; a new field of rve::Rve::State is a line in rve_state_fields.h alone.
struct PointCheckpoint {
  Mat3 stress = Mat3::Zero();               //!< last homogenised stress, physical frame
  double substeps = 0.0;                    //!< DEM steps of its last update
  rve::Rve::State rve;                      //!< rotation, streaming gradient, counters
  double work[DemWork::kValues] = {};       //!< the point's DEM work (DemWork row)
  double quiet[QuietPoints::kValues] = {};  //!< its quiet-point state (QuietPoints row)
  double flow[SteadyFlow::kValues] = {};    //!< its steady-flow state (SteadyFlow row)
};

//! Doubles per point when packed (the sum of the field widths).
std::size_t point_checkpoint_width();
//! Append `p` to `row` (point_checkpoint_width() values).
void pack(const PointCheckpoint& p, std::vector<double>& row);
//! The point packed at `row`.
PointCheckpoint unpack(const double* row);

//! Store the packed points `rows` (all points, in order) as one array per field.
void write_points(materials::CheckpointWriter& out, const std::vector<double>& rows);
//! The packed points of a checkpoint; throws naming the field when a field is missing,
//! unknown fields were saved, or the number of points is not `points`.
std::vector<double> read_points(const materials::CheckpointReader& in, std::size_t points);

}  // namespace mpm_lig::coupling
