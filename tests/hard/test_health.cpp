// Hard case: the RVE health check tells a blow-up from a packing without contacts. A packing
// deformed far too fast for its DEM steps must be stopped with a message; the same packing
// pulled apart until its contacts are gone (stress 0, grains moving) must not be.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/case_node.h"
#include "rve/consolidation.h"
#include "rve/rve.h"

using namespace mpm_lig;

namespace {

rve::RveSpec spec_60_discs() {
  const auto doc = CaseDocument::parse(R"({"rve": {"dimension": 2, "grains": 60,
      "radius": {"min": 0.003, "max": 0.007}, "density": 2650, "seed": 3,
      "contact": {"youngs_modulus": 6e8, "stiffness_ratio": 0.8, "friction_deg": 28.6,
                  "damping_ratio": 0.1},
      "time_step_fraction": 0.15, "preparation": {"confining_pressure": 1e5},
      "substeps": {"fixed": 50}}})");
  return rve::parse_rve_spec(doc.root().child("rve"));
}

//! Runs `steps` DEM steps at rest and returns the health message ("" when healthy).
std::string health_after(rve::Rve& rve, int steps, rve::Observables& now) {
  rve.relax(steps);
  now = rve.observe();
  try {
    rve.check_health(now);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// A deformation far too fast for the DEM: 2 % compression per DEM step with positions remapped
// (no streaming velocity to carry the grains), up to 30 times over. The overlaps outgrow the
// contact law within a few steps. Measured (60 discs, 100 kPa): healthy start with the largest
// overlap 0.045 of the smaller radius and 3e-5 radii per step.
TEST(HardHealth, DeformationFarTooFastIsCaught) {
  rve::RveSpec spec = spec_60_discs();
  spec.stream_velocity = false;
  auto rve = rve::Rve::generate(spec, MPI_COMM_WORLD, "blow-up RVE");
  rve::consolidate(*rve);
  rve::Observables now;
  ASSERT_EQ(health_after(*rve, 200, now), "");
  const double healthy_overlap = now.max_overlap_ratio;
  Mat3 squeeze = Mat3::Identity();
  squeeze(0, 0) = squeeze(1, 1) = 0.98;
  std::string message;
  int increments = 0;
  for (; increments < 30 && message.empty(); ++increments) {
    rve->deform(squeeze, 1);
    message = health_after(*rve, 1, now);
    std::printf("%d: overlap %.3f, travel %.2e\n", increments, now.max_overlap_ratio,
                now.step_travel);
  }
  std::printf("caught after %d increments: %s (largest overlap at rest %.3f)\n", increments,
              message.c_str(), healthy_overlap);
  EXPECT_NE(message.find("blow-up RVE"), std::string::npos) << message;
  EXPECT_NE(message.find("blow-up"), std::string::npos) << message;
  EXPECT_LT(healthy_overlap, 0.2 * rve::kMaxOverlapRatio);
}

// An extension that opens every contact: elastic energy 0, grains still moving with the flow;
// healthy however large kinetic/elastic becomes.
TEST(HardHealth, PackingWithoutContactsIsHealthy) {
  const rve::RveSpec spec = spec_60_discs();
  auto rve = rve::Rve::generate(spec, MPI_COMM_WORLD, "loose RVE");
  rve::consolidate(*rve);
  Mat3 stretch = Mat3::Identity();
  stretch(0, 0) = stretch(1, 1) = 1.002;
  rve::Observables now;
  for (int k = 0; k < 100; ++k) {
    rve->deform(stretch);
    now = rve->observe();
    ASSERT_NO_THROW(rve->check_health(now)) << "increment " << k;
  }
  EXPECT_LT(mean_pressure(now.stress, 2), 1.0);  // Pa: every contact open
  EXPECT_EQ(now.grains, spec.grains);
}
