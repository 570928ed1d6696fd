// The homogenised stress of a deformed LAMMPS RVE equals Σ r⊗f / V over its contacts.
#include <gtest/gtest.h>

#include "core/case_node.h"
#include "rve/consolidation.h"
#include "rve/rve.h"

using namespace mpm_lig;

TEST(RveLammps, StressEqualsContactSumAfterDeformation) {
  const auto doc = CaseDocument::parse(R"({"rve": {"engine": "lammps", "dimension": 3,
      "grains": 100, "radius": {"min": 0.003, "max": 0.007}, "density": 2650, "seed": 5,
      "contact": {"youngs_modulus": 7e8, "poisson_ratio": 0.3, "friction": 0.5,
                  "damping_ratio": 0.1},
      "time_step_fraction": 0.15, "preparation": {"confining_pressure": 1e5},
      "substeps": {"fixed": 50}}})");
  const rve::RveSpec spec = rve::parse_rve_spec(doc.root().child("rve"));
  auto r = rve::Rve::generate(spec, MPI_COMM_WORLD, "lammps RVE");
  // Compress until the packing carries load, then shear it.
  Mat3 dF = Mat3::Identity() * (1.0 - 2e-3);
  for (int k = 0; k < 400 && rve::mean_stress(r->stress(), 3) < 2e4; ++k)
    r->deform(dF, 50);
  Mat3 shear = Mat3::Identity();
  shear(0, 2) = 2e-3;
  r->deform(shear, 100);
  r->engine().command("run 0");  // virial and contact list of the same force evaluation
  const Mat3 s = r->stress();
  ASSERT_GT(rve::mean_stress(s, 3), 0.0);
  const Mat3 from_contacts = rve::contact_stress(r->engine().contacts(), r->volume());
  const Voigt6 a = to_voigt(s), b = to_voigt(from_contacts);  // upper components
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(a[i], b[i], 1e-6 * s.norm()) << kVoigtNames[i];
}
