#pragma once

#include <memory>
#include <string>

#include "core/case_node.h"
#include "element/recorded_path.h"
#include "rve/spec.h"

namespace mpm_lig::element {

//! Which strain path an element test follows.
enum class TestKind {
  kIsotropicCompression,
  kDrainedCompression,
  kUndrainedCyclicSimpleShear,
  kRecordedPath,  //!< a recorded deformation history F(t) replayed (recorded_path.h)
};

//! The "analysis" node of an element test, validated.
struct ElementTestSpec {
  TestKind kind = TestKind::kIsotropicCompression;
  std::string name;                    //!< as written in the case ("drained_triaxial", ...)
  double strain_increment = 1e-4;      //!< per increment (axial, per-axis or shear strain)
  double strain = 0.0;                 //!< total: per-axis (isotropic) or axial (drained) strain
  double confining_pressure = 0.0;     //!< drained: lateral stress [Pa]; 0 = preparation pressure
  double confining_tolerance = 0.005;  //!< drained: relative tolerance of the lateral stress
  int max_corrections = 20;            //!< drained: lateral corrections per increment at most
  double shear_amplitude = 0.0;        //!< cyclic: engineering shear strain amplitude γ_a
  int cycles = 0;
  //! recorded_path: the whole path, read and checked when the case is (shared: specs are copied)
  std::shared_ptr<const RecordedPath> recorded;
  int output_every = 1;      //!< history row every N increments
  int snapshot_every = 0;    //!< VTK snapshot every N increments (0: first and last only)
  bool save_restart = true;  //!< write the prepared packing to DIR/prepared.restart
};

//! Parse and validate `analysis` (the node whose "type" is "element_test") for `rve`; a
//! recorded path's file is read and checked here, before anything is created.
ElementTestSpec parse_element_test(const CaseNode& analysis, const rve::RveSpec& rve);

}  // namespace mpm_lig::element
