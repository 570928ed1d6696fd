#include "element/element_spec.h"

#include <algorithm>

namespace mpm_lig::element {
namespace {

//! Most strain increments an element test may take (each is at least one DEM run).
constexpr double kMaxIncrements = 1e9;

//! The keys of a test that follows a strain path it computes itself (not a recorded one).
void parse_computed_path(const CaseNode& a, ElementTestSpec& t) {
  t.strain_increment = a.in_range_or("strain_increment", 1e-7, 0.01, 1e-4);
  if (t.name == "isotropic_compression") {
    t.kind = TestKind::kIsotropicCompression;
    t.strain = a.in_range("strain", 1e-7, 0.5);
  } else if (t.name == "undrained_cyclic_simple_shear") {
    t.kind = TestKind::kUndrainedCyclicSimpleShear;
    t.shear_amplitude = a.in_range("shear_strain_amplitude", 1e-7, 2.0);
    t.cycles = a.get<int>("cycles");
    // Four quarter cycles of amplitude / increment each; the count must stay a sane loop.
    if (t.cycles < 1 || 4.0 * t.cycles * t.shear_amplitude / t.strain_increment > kMaxIncrements)
      a.fail("cycles", "must be >= 1 and take at most " + std::to_string(long(kMaxIncrements)) +
                           " strain increments");
  } else {
    t.kind = TestKind::kDrainedCompression;
    t.strain = a.in_range("axial_strain", 1e-7, 0.7);
    t.confining_pressure = a.positive_or("confining_pressure", 0.0);
    t.confining_tolerance = a.in_range_or("confining_tolerance", 1e-4, 0.1, 0.005);
    t.max_corrections = a.get_or<int>("max_corrections", 20);
    if (t.max_corrections < 0)
      a.fail("max_corrections", "must be >= 0");
  }
  if (t.strain_increment > std::max(t.strain, t.shear_amplitude))
    a.fail("strain_increment", "is larger than the total strain of the test");
}

}  // namespace

ElementTestSpec parse_element_test(const CaseNode& a, const rve::RveSpec& rve) {
  ElementTestSpec t;
  const std::string test2d = "drained_biaxial", test3d = "drained_triaxial";
  t.name = a.choice("test", {"isotropic_compression", test2d, test3d,
                             "undrained_cyclic_simple_shear", "recorded_path"});
  if ((t.name == test2d && rve.dimension != 2) || (t.name == test3d && rve.dimension != 3))
    a.fail("test", t.name + " needs an RVE of dimension " + (t.name == test2d ? "2" : "3") + " (" +
                       rve.path + ".dimension is " + std::to_string(rve.dimension) + ")");
  t.output_every = a.get_or<int>("output_every", 1);
  if (t.output_every < 1)
    a.fail("output_every", "must be >= 1");
  t.snapshot_every = a.get_or<int>("snapshot_every", 0);
  if (t.snapshot_every < 0)
    a.fail("snapshot_every", "must be >= 0");
  t.save_restart = a.get_or<bool>("save_restart", true);
  if (t.name == "recorded_path") {
    // The increments are the recorded ones: no strain_increment (an unused key is an error).
    t.kind = TestKind::kRecordedPath;
    t.recorded = read_recorded_path(a.child("path"), rve.dimension);
    if (static_cast<double>(t.recorded->intervals()) > kMaxIncrements)
      a.fail("path", "more than " + std::to_string(long(kMaxIncrements)) + " recorded intervals");
  } else {
    parse_computed_path(a, t);
  }
  return t;
}

}  // namespace mpm_lig::element
