#include <cmath>

#include <gtest/gtest.h>

#include "driver.h"
#include "materials/drucker_prager.h"

namespace mpm_lig::materials {
namespace {

using testing::step;
using Match = DruckerPragerCone::Match;

const Elasticity kElastic = Elasticity::from_moduli(20e6, 0.3);

TEST(DruckerPrager, PlaneStrainMatchGivesMohrCoulombPlaneStrainStrength) {
  // Associated flow, simple shear at constant vertical stress: τ/σ_n = tan φ, as for
  // Mohr–Coulomb (Davis with ψ = φ).
  const double phi = 30.0 * kDegree, vertical = 100e3;
  DruckerPrager m(1800.0, kElastic, DruckerPragerCone::matched(Match::plane_strain, 0, phi, phi));
  m.add_points(1);
  const Mat3 s = testing::simple_shear_at_constant_vertical_stress(m, vertical, 400, 2.5e-4);
  EXPECT_NEAR(std::abs(s(0, 1)) / vertical, std::tan(phi), 5e-3 * std::tan(phi));
  EXPECT_GT(m.state(0, 1), 0.0);  // associated: it dilates
}

TEST(DruckerPrager, CompressionMatchGivesMohrCoulombTriaxialStrength) {
  const double c = 10e3, phi = 30.0 * kDegree, confining = 100e3;
  DruckerPrager m(1800.0, kElastic,
                  DruckerPragerCone::matched(Match::triaxial_compression, c, phi, 0.0));
  m.add_points(1);
  const Mat3 s = testing::triaxial_compression(m, confining, 300, 1e-4);
  const double sf = std::sin(phi);
  const double limit = (1.0 + sf) / (1.0 - sf) * confining + 2.0 * c * std::cos(phi) / (1.0 - sf);
  EXPECT_NEAR(-s(2, 2), limit, 1e-6 * limit);
}

TEST(DruckerPrager, TensionReturnsToTheApex) {
  const DruckerPragerCone cone =
      DruckerPragerCone::matched(Match::plane_strain, 5e3, 35.0 * kDegree, 5.0 * kDegree);
  DruckerPrager m(1800.0, kElastic, cone);
  m.add_points(1);
  Mat3 dF = (1.0 + 1e-3) * Mat3::Identity();
  dF(0, 1) = 3e-4;
  Mat3 s;
  for (int i = 0; i < 200; ++i)
    s = step(m, 0, dF);
  EXPECT_LT((s - cone.xi_c / cone.eta * Mat3::Identity()).norm(), 1e-9 * cone.xi_c / cone.eta);
}

}  // namespace
}  // namespace mpm_lig::materials
