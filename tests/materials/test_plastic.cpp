#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "driver.h"
#include "materials/plastic.h"
#include "materials/principal.h"

namespace mpm_lig::materials {
namespace {

using testing::rotation;
using testing::step;

const Elasticity kElastic = Elasticity::from_moduli(20e6, 0.3);

//! Isochoric pure shear in the xy plane without spin (principal stretches e^±γ/2 at 45°):
//! engineering shear strain γ, no volume change, dF symmetric.
Mat3 pure_shear(double dgamma) {
  Mat3 dF = Mat3::Identity();
  dF(0, 0) = dF(1, 1) = std::cosh(0.5 * dgamma);
  dF(0, 1) = dF(1, 0) = std::sinh(0.5 * dgamma);
  return dF;
}

TEST(VonMises, PlaneStrainShearLimitIsTheUndrainedStrength) {
  const double cu = 50e3;
  VonMises m(1800.0, kElastic, std::sqrt(3.0) * cu);
  m.add_points(1);
  m.set_stress(0, -100e3 * Mat3::Identity());
  const double yield_strain = cu / kElastic.shear;
  Mat3 s;
  for (int i = 0; i < 4000; ++i) {
    s = step(m, 0, pure_shear(0.02 * yield_strain));
    if (i * 0.02 > 1.5) {  // past first yield: on the surface every step
      ASSERT_NEAR(deviatoric_stress(s), std::sqrt(3.0) * cu, 1e-9 * cu) << i;
    }
  }
  // Associated J2 flow in plane strain drives s_zz to zero: τ → q_y / √3 = c_u.
  EXPECT_NEAR(s(0, 1), cu, 1e-6 * cu);
  EXPECT_NEAR(mean_pressure(s), 100e3, 1e-6 * cu);  // no plastic volume change
  // ε_q = γ/√3 in pure shear; plastic after the first γ_y = c_u / G.
  EXPECT_NEAR(m.state(0, 0), (80.0 - 1.0) * yield_strain / std::sqrt(3.0), 0.05 * yield_strain);
  EXPECT_EQ(m.state(0, 1), 0.0);
}

TEST(VonMises, SimpleShearStaysOnTheSurfaceAndReachesTheUndrainedStrength) {
  const double cu = 50e3;
  VonMises m(1800.0, kElastic, std::sqrt(3.0) * cu);
  m.add_points(1);
  Mat3 dF = Mat3::Identity();
  dF(0, 1) = 0.05 * cu / kElastic.shear;
  Mat3 s;
  for (int i = 0; i < 2000; ++i) {
    s = step(m, 0, dF);
    if (i > 40) {
      ASSERT_NEAR(deviatoric_stress(s), std::sqrt(3.0) * cu, 1e-9 * cu) << i;
    }
  }
  // Jaumann spin keeps small normal deviators (of order c_u / G) in simple shear.
  EXPECT_NEAR(s(0, 1), cu, 1e-3 * cu);
}

TEST(VonMises, SoftensLinearlyWithPlasticStrainToItsResidual) {
  // q_y(κ) = max(q_y0 − H κ, q_r): in pure shear after first yield the point stays on the
  // softening line, step by step (the return is exact for linear softening), then on q_r.
  const double qy = 100e3, residual = 40e3, modulus = 0.1 * 3.0 * kElastic.shear;
  VonMises m(1800.0, kElastic, qy, Softening{modulus, residual});
  m.add_points(1);
  m.set_stress(0, -100e3 * Mat3::Identity());
  const double step_strain = 0.01 * qy / (std::sqrt(3.0) * kElastic.shear);
  bool softened = false;
  for (int i = 0; i < 3000; ++i) {
    const Mat3 s = step(m, 0, pure_shear(step_strain));
    const double kappa = m.state(0, 0);
    if (kappa > 0.0) {
      ASSERT_NEAR(deviatoric_stress(s), std::max(qy - modulus * kappa, residual), 1e-9 * qy) << i;
      softened |= deviatoric_stress(s) < 0.9 * qy;
    }
    EXPECT_NEAR(mean_pressure(s), 100e3, 1e-6 * qy);
  }
  EXPECT_TRUE(softened);
  EXPECT_GT(m.state(0, 0), (qy - residual) / modulus);  // reached the residual plateau
  // Without softening the same material is the perfectly plastic one, bit for bit.
  VonMises perfect(1800.0, kElastic, qy), zero(1800.0, kElastic, qy, Softening{0.0, 0.0});
  perfect.add_points(1);
  zero.add_points(1);
  for (int i = 0; i < 300; ++i)
    ASSERT_EQ(step(perfect, 0, pure_shear(step_strain)), step(zero, 0, pure_shear(step_strain)));
}

TEST(Tresca, IsMohrCoulombWithoutFrictionAndLimitsShearToTheUndrainedStrength) {
  const double cu = 40e3;
  MohrCoulombStrength tresca;
  tresca.cohesion = cu;
  MohrCoulomb m("tresca", 1800.0, kElastic, tresca);
  m.add_points(1);
  m.set_stress(0, -80e3 * Mat3::Identity());
  Mat3 s;
  for (int i = 0; i < 2000; ++i)
    s = step(m, 0, pure_shear(0.05 * cu / kElastic.shear));
  const Principal p = principal(s);
  EXPECT_NEAR(p.values[0] - p.values[2], 2.0 * cu, 1e-9 * cu);
  EXPECT_NEAR(s(0, 1), cu, 1e-6 * cu);
}

MohrCoulombStrength mohr_coulomb(double c, double phi_deg, double psi_deg) {
  MohrCoulombStrength s;
  s.cohesion = c;
  s.friction = phi_deg * kDegree;
  s.dilatancy = psi_deg * kDegree;
  return s;
}

TEST(MohrCoulomb, TriaxialCompressionLimitMatchesTheClosedForm) {
  for (const double psi : {0.0, 15.0, 30.0}) {
    const double c = 10e3, phi = 30.0, confining = 100e3;
    MohrCoulomb m("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(c, phi, psi));
    m.add_points(1);
    const Mat3 s = testing::triaxial_compression(m, confining, 300, 1e-4);
    const double sf = std::sin(phi * kDegree), cf = std::cos(phi * kDegree);
    const double limit = (1.0 + sf) / (1.0 - sf) * confining + 2.0 * c * cf / (1.0 - sf);
    EXPECT_NEAR(-s(2, 2), limit, 1e-6 * limit) << "psi " << psi;
    EXPECT_NEAR(s(0, 0), -confining, 1e-6 * confining);
    // Dilatancy: plastic volumetric over deviatoric strain rate tracks ψ (0 for ψ = 0).
    EXPECT_EQ(m.state(0, 1) > 1e-6, psi > 0.0) << "psi " << psi;
  }
}

TEST(MohrCoulomb, PlaneStrainSimpleShearLimitMatchesDavis) {
  // Simple shear at constant vertical stress, no horizontal strain: at failure
  // τ/σ_n = sin φ cos ψ / (1 − sin φ sin ψ) (c = 0).
  for (const double psi : {0.0, 10.0, 30.0}) {
    const double phi = 30.0, vertical = 100e3;
    MohrCoulomb m("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(0.0, phi, psi));
    m.add_points(1);
    const Mat3 s = testing::simple_shear_at_constant_vertical_stress(m, vertical, 400, 2.5e-4);
    const double sf = std::sin(phi * kDegree), sd = std::sin(psi * kDegree);
    const double ratio = sf * std::cos(psi * kDegree) / (1.0 - sf * sd);
    // The Jaumann spin shifts the steady state by O(σ/G) = O(1e-3).
    EXPECT_NEAR(std::abs(s(0, 1)) / vertical, ratio, 5e-3 * ratio) << "psi " << psi;
    EXPECT_NEAR(s(1, 1), -vertical, 1e-6 * vertical);
  }
}

TEST(MohrCoulomb, SofteningAnglesFollowThePlasticStrainToTheResidual) {
  // Drained triaxial compression: on the surface σ1/σ3 = (1 + sin φ)/(1 − sin φ) exactly, for
  // the φ of the plastic strain κ at the step's start (the strength is explicit in κ), step by
  // step down to the residual angle; then simple shear ends on Davis's residual limit.
  const double confining = 100e3, kappa_r = 0.05;
  const double phi_p = 32.0, psi_p = 8.0, phi_r = 20.0, psi_r = 0.0;
  const FrictionSoftening softening{phi_r * kDegree, psi_r * kDegree, kappa_r};
  MohrCoulomb m("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(0.0, phi_p, psi_p), softening);
  m.add_points(1);
  testing::triaxial_compression(m, confining, 0, 0.0);  // the isotropic start
  bool yielded = false;
  for (int i = 0; i < 1500; ++i) {
    const double kappa = m.state(0, 0);
    const double phi = (phi_p + std::min(kappa / kappa_r, 1.0) * (phi_r - phi_p)) * kDegree;
    Mat3 dF = Mat3::Identity();
    dF(2, 2) = 1.0 - 1e-4;
    const Mat3 s = testing::mixed_step(m, dF, {{0, 1}}, Vec3(-confining, -confining, 0.0));
    if (m.state(0, 0) > kappa) {
      yielded = true;
      const double ratio = (1.0 + std::sin(phi)) / (1.0 - std::sin(phi));
      ASSERT_NEAR(s(2, 2) / s(0, 0), ratio, 1e-6 * ratio) << i << " kappa " << kappa;
    }
  }
  EXPECT_TRUE(yielded);
  EXPECT_GT(m.state(0, 0), kappa_r);  // reached the residual angle
  MohrCoulomb shear("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(0.0, phi_p, psi_p), softening);
  shear.add_points(1);
  const Mat3 s = testing::simple_shear_at_constant_vertical_stress(shear, confining, 2400, 2.5e-4);
  EXPECT_GT(shear.state(0, 0), kappa_r);
  const double sf = std::sin(phi_r * kDegree);
  EXPECT_NEAR(std::abs(s(0, 1)) / confining, sf, 5e-3 * sf);  // Davis with ψ_r = 0: sin φ_r
  // Without softening (κ_r = 0) the same material is the perfectly plastic one, bit for bit.
  MohrCoulomb perfect("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(0.0, phi_p, psi_p));
  MohrCoulomb zero("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(0.0, phi_p, psi_p),
                   FrictionSoftening{phi_r * kDegree, psi_r * kDegree, 0.0});
  perfect.add_points(1);
  zero.add_points(1);
  for (int i = 0; i < 300; ++i)
    ASSERT_EQ(step(perfect, 0, pure_shear(1e-4)), step(zero, 0, pure_shear(1e-4))) << i;
}

TEST(MohrCoulomb, IsotropicTensionReturnsToTheApexSafely) {
  for (const double c : {0.0, 5e3}) {
    MohrCoulomb m("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(c, 35.0, 5.0));
    m.add_points(1);
    Mat3 dF = (1.0 + 1e-3) * Mat3::Identity();
    dF(0, 1) = 3e-4;  // a little shear on top
    Mat3 s;
    for (int i = 0; i < 200; ++i)
      s = step(m, 0, dF);
    ASSERT_TRUE(s.allFinite());
    const double apex = c / std::tan(35.0 * kDegree);
    EXPECT_LT((s - apex * Mat3::Identity()).norm(), 1e-9 * (apex + kElastic.shear * 1e-6));
    EXPECT_GT(m.state(0, 1), 0.0);  // opened up plastically
  }
}

TEST(MohrCoulomb, TensionCutoffCapsTheLargestPrincipalStress) {
  MohrCoulombStrength strength = mohr_coulomb(20e3, 30.0, 0.0);
  strength.tension_cutoff = 5e3;
  MohrCoulomb m("mohr_coulomb", 1800.0, kElastic, strength);
  m.add_points(1);
  m.set_stress(0, -10e3 * Mat3::Identity());
  Mat3 dF = Mat3::Identity();
  dF(0, 0) = 1.0 + 2e-4;  // uniaxial extension
  for (int i = 0; i < 200; ++i) {
    const Principal p = principal(step(m, 0, dF));
    ASSERT_LE(p.values[0], 5e3 * (1.0 + 1e-12)) << i;
    ASSERT_LE(strength.yield(p.values), 1e-9 * 20e3) << i;
  }
}

//! Energy norm of a principal stress difference, (Δσ · D^-1 Δσ)^1/2.
double energy(const Vec3& d) {
  return std::sqrt(d.dot(plastic_strain(d, Vec3::Zero(), kElastic)));
}

TEST(MohrCoulombReturn, RandomTrialsLandOnTheSurfaceAtTheClosestPoint) {
  // With associated flow (ψ = φ) the return is the closest admissible point in the energy
  // norm; check against many other admissible points, across plane, edge and apex returns.
  const MohrCoulombStrength s = mohr_coulomb(10e3, 30.0, 30.0);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-200e3, 100e3);
  std::vector<Vec3> admissible;
  int kinds[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < 3000; ++i) {
    Vec3 trial(uniform(random), uniform(random), uniform(random));
    std::sort(trial.data(), trial.data() + 3, std::greater<double>());
    ReturnKind kind;
    const Vec3 r = mohr_coulomb_return(trial, kElastic, s, &kind);
    ++kinds[static_cast<int>(kind)];
    ASSERT_LE(s.yield(r), 1e-9 * 300e3) << i;
    ASSERT_GE(r[0] - r[1], -1e-6) << i;
    ASSERT_GE(r[1] - r[2], -1e-6) << i;
    if (kind != ReturnKind::elastic) {
      ASSERT_NEAR(s.yield(r), 0.0, 1e-9 * 300e3) << i;
    }
    for (const Vec3& other : admissible)
      ASSERT_LE(energy(trial - r), energy(trial - other) * (1.0 + 1e-9)) << i;
    if (i % 10 == 0)
      admissible.push_back(r);
  }
  EXPECT_GT(kinds[static_cast<int>(ReturnKind::plane)], 100);
  EXPECT_GT(kinds[static_cast<int>(ReturnKind::edge)], 100);
  EXPECT_GT(kinds[static_cast<int>(ReturnKind::apex)], 20);
}

TEST(MohrCoulombReturn, NonAssociatedAndTrescaReturnsAreAdmissibleAndFinite) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-200e3, 100e3);
  MohrCoulombStrength cutoff = mohr_coulomb(10e3, 35.0, 0.0);
  cutoff.tension_cutoff = 2e3;
  for (const MohrCoulombStrength& s : {mohr_coulomb(0.0, 30.0, 0.0), mohr_coulomb(10e3, 40.0, 10.0),
                                       mohr_coulomb(40e3, 0.0, 0.0), cutoff}) {
    for (int i = 0; i < 2000; ++i) {
      Vec3 trial(uniform(random), uniform(random), uniform(random));
      std::sort(trial.data(), trial.data() + 3, std::greater<double>());
      ReturnKind kind;
      const Vec3 r = mohr_coulomb_return(trial, kElastic, s, &kind);
      ASSERT_TRUE(r.allFinite());
      ASSERT_LE(s.yield(r), 1e-9 * 200e3) << i;
      ASSERT_LE(r[0], s.tension_cutoff + 1e-9 * 200e3) << i;
      ASSERT_GE(r[0] - r[1], -1e-6) << i;
      ASSERT_GE(r[1] - r[2], -1e-6) << i;
      // The plastic strain follows the flow rule: its volumetric part is dilation, never
      // compaction, and none at all for ψ = 0 unless the apex or the cutoff was reached.
      const Vec3 ep = plastic_strain(trial, r, kElastic);
      ASSERT_GE(ep.sum(), -1e-12) << i;
      if (s.dilatancy == 0.0 && (kind == ReturnKind::plane || kind == ReturnKind::edge)) {
        ASSERT_NEAR(ep.sum(), 0.0, 1e-12) << i;
      }
    }
  }
}

TEST(MohrCoulomb, LongRandomLargeStrainHistoryStaysAdmissibleAndFinite) {
  // What a point under a footing meets: many increments of mixed compression, extension,
  // shear and rotation, total strains far beyond 100 %.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-0.01, 0.01);
  for (const MohrCoulombStrength& s : {mohr_coulomb(0.0, 30.0, 0.0), mohr_coulomb(40e3, 0.0, 0.0),
                                       mohr_coulomb(5e3, 40.0, 10.0)}) {
    MohrCoulomb m("mohr_coulomb", 1800.0, kElastic, s);
    m.add_points(1);
    m.set_stress(0, -50e3 * Mat3::Identity());
    for (int i = 0; i < 5000; ++i) {
      Mat3 dF = Mat3::Identity();
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          dF(a, b) += uniform(random);
      const Mat3 stress = step(m, 0, dF);
      ASSERT_TRUE(stress.allFinite()) << i;
      ASSERT_LE(s.yield(principal(stress).values), 1e-8 * 50e3) << i;
      ASSERT_EQ(stress(0, 2), 0.0);  // plane strain stays plane
    }
    EXPECT_GT(m.state(0, 0), 0.3);  // well into large plastic strain
  }
}

TEST(MohrCoulomb, RigidRotationOfAYieldingPointChangesNothingButTheAxes) {
  MohrCoulomb m("mohr_coulomb", 1800.0, kElastic, mohr_coulomb(5e3, 30.0, 0.0));
  m.add_points(1);
  Mat3 s0;
  s0 << -100e3, 0, 0, 0, -100e3, 0, 0, 0, -100e3;
  m.set_stress(0, s0);
  for (int i = 0; i < 100; ++i)  // shear it to failure first
    s0 = step(m, 0, pure_shear(1e-4));
  const double plastic = m.state(0, 0);
  const Mat3 q = rotation(Vec3(0, 0, 1), 0.5 * kPi);
  Mat3 s;
  for (int i = 0; i < 500; ++i)
    s = step(m, 0, rotation(Vec3(0, 0, 1), 0.5 * kPi / 500));
  EXPECT_LT((s - q * s0 * q.transpose()).norm(), 1e-9 * s0.norm());
  // Round-off in dF − I (1e-16 × 2G per step) may nudge f past its 1e-12 tolerance: the
  // plastic strain may change by round-off, not more.
  EXPECT_NEAR(m.state(0, 0), plastic, 1e-12);
}

}  // namespace
}  // namespace mpm_lig::materials
