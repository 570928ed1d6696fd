// Preparation towards a target void ratio: compaction with lowered friction, then the real
// friction restored and the packing re-consolidated to the target pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/case_node.h"
#include "dem/engine.h"
#include "rve/consolidation.h"
#include "rve/observables.h"
#include "rve/rve.h"
#include "test_rve_spec.h"

using namespace mpm_lig;

namespace {

constexpr double kPressure = 1e5;

rve::RveSpec spec_with(const std::string& preparation, int dimension = 2, int grains = 100) {
  const auto doc = CaseDocument::parse(R"({"rve": {"dimension": )" + std::to_string(dimension) +
                                       R"(, "grains": )" + std::to_string(grains) + R"(,
      "radius": {"min": 0.003, "max": 0.007}, "density": 2650, "seed": 11,
      "contact": {"youngs_modulus": 7e8, "poisson_ratio": 0.3, "friction": 0.5,
                  "damping_ratio": 0.1},
      "time_step_fraction": 0.15, "preparation": )" +
                                       preparation + R"(, "substeps": {"fixed": 50}}})");
  return rve::parse_rve_spec(doc.root().child("rve"));
}

}  // namespace

// The target lies 0.02 below the void ratio the full friction gives at the same pressure.
// Measured (100 discs, friction 0.5): e = 0.2283 with full friction.
TEST(RveCompaction, ReachesTargetVoidRatioAndRestoresFriction) {
  auto reference = rve::Rve::generate(spec_with(R"({"confining_pressure": 1e5})"), MPI_COMM_WORLD,
                                      "full friction");
  const rve::ConsolidationResult full = rve::consolidate(*reference);
  const double target = full.final.void_ratio - 0.02;
  const rve::RveSpec spec = spec_with(R"({"confining_pressure": 1e5, "target_void_ratio": )" +
                                      std::to_string(target) + "}");
  auto dense = rve::Rve::generate(spec, MPI_COMM_WORLD, "compacted");
  const rve::ConsolidationResult c = rve::consolidate(*dense);
  std::printf("2D: target %.4f reached %.4f (error %+.4f, friction %.4f)\n", target,
              c.final.void_ratio, c.void_ratio_error, c.friction_used);
  EXPECT_TRUE(c.void_ratio_reached);
  EXPECT_NO_THROW(rve::require_void_ratio(*dense, c));
  EXPECT_DOUBLE_EQ(c.void_ratio_error, c.final.void_ratio - *spec.preparation.target_void_ratio);
  EXPECT_LT(c.friction_used, spec.contact.friction);
  // Compaction stages stop as the void ratio crosses the upper half of the band;
  // re-consolidating with the real friction moves it by a few 1e-3 at most.
  EXPECT_NEAR(c.final.void_ratio, target, spec.preparation.void_ratio_tolerance);
  EXPECT_NEAR(mean_pressure(c.final.stress, 2), kPressure, spec.preparation.tolerance * kPressure);
  EXPECT_LT(c.final.kinetic_ratio(), 0.01);
  // Friction restored: a denser packing with the real friction is at least as strong in
  // shear as the looser reference (a frictionless one would lose most of its strength).
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 2e-3;
  for (int k = 0; k < 10; ++k) {
    reference->deform(shear);
    dense->deform(shear);
  }
  const Mat3 s_ref = reference->stress(), s_dense = dense->stress();
  EXPECT_GT(deviatoric_stress(s_dense, 2) / mean_pressure(s_dense, 2),
            0.9 * deviatoric_stress(s_ref, 2) / mean_pressure(s_ref, 2));
}

// A target looser than the full friction packs: the contact law alone cannot reach it
// (preparation only densifies), a first consolidation at a higher friction can: it packs
// looser, the staged lowering passes through the real friction, and the real friction is what
// the packing ends with. Measured (100 discs, friction 0.5): e = 0.2283; at 45° first 0.24.
TEST(RveCompaction, LooserTargetReachedWithConsolidationFriction) {
  auto reference = rve::Rve::generate(spec_with(R"({"confining_pressure": 1e5})"), MPI_COMM_WORLD,
                                      "full friction");
  const double full = rve::consolidate(*reference).final.void_ratio;
  const std::string target = std::to_string(full + 0.007);
  const rve::RveSpec plain =
      spec_with(R"({"confining_pressure": 1e5, "target_void_ratio": )" + target + "}");
  auto without = rve::Rve::generate(plain, MPI_COMM_WORLD, "without");
  const rve::ConsolidationResult w = rve::consolidate(*without);
  EXPECT_FALSE(w.void_ratio_reached);
  EXPECT_THROW(rve::require_void_ratio(*without, w), std::runtime_error);

  const rve::RveSpec looser = spec_with(R"({"confining_pressure": 1e5, "target_void_ratio": )" +
                                        target + R"(, "consolidation_friction_deg": 45})");
  auto with = rve::Rve::generate(looser, MPI_COMM_WORLD, "with");
  const rve::ConsolidationResult c = rve::consolidate(*with);
  std::printf(
      "2D looser: full friction %.4f, target %s, reached %.4f (compacted %.4f at "
      "friction %.4f)\n",
      full, target.c_str(), c.final.void_ratio, c.compacted_void_ratio, c.friction_used);
  EXPECT_TRUE(c.void_ratio_reached);
  EXPECT_NO_THROW(rve::require_void_ratio(*with, c));
  EXPECT_GT(c.final.void_ratio, full + 0.002);
  EXPECT_NEAR(mean_pressure(c.final.stress, 2), kPressure,
              looser.preparation.tolerance * kPressure);
}

// 3D (60 spheres), target 0.03 below the full-friction void ratio: the staged compaction does
// not always land within the tolerance in 3D (measured: -0.0047, and -0.0087 after a round-off
// change of the DEM; 400 spheres -0.006 and -0.019), so what is guaranteed is checked: the
// pressure on target, the miss reported exactly, and a miss refused with a message.
TEST(RveCompaction, TargetVoidRatioIn3dReachedOrRefused) {
  auto reference = rve::Rve::generate(spec_with(R"({"confining_pressure": 1e5})", 3, 60),
                                      MPI_COMM_WORLD, "3D full friction");
  const double full = rve::consolidate(*reference).final.void_ratio;
  const rve::RveSpec spec = spec_with(
      R"({"confining_pressure": 1e5, "target_void_ratio": )" + std::to_string(full - 0.03) + "}", 3,
      60);
  const double target = *spec.preparation.target_void_ratio;
  auto dense = rve::Rve::generate(spec, MPI_COMM_WORLD, "3D compacted");
  const rve::ConsolidationResult c = rve::consolidate(*dense);
  std::printf("3D: target %.4f reached %.4f (error %+.4f, friction %.4f)\n", target,
              c.final.void_ratio, c.void_ratio_error, c.friction_used);
  EXPECT_DOUBLE_EQ(c.void_ratio_error, c.final.void_ratio - target);
  EXPECT_EQ(c.void_ratio_reached,
            std::abs(c.void_ratio_error) <= spec.preparation.void_ratio_tolerance);
  EXPECT_LT(c.final.void_ratio, full - 0.01);  // compacted well below the full-friction value
  EXPECT_NEAR(mean_pressure(c.final.stress, 3), kPressure, spec.preparation.tolerance * kPressure);
  if (c.void_ratio_reached)
    EXPECT_NO_THROW(rve::require_void_ratio(*dense, c));
  else
    EXPECT_THROW(rve::require_void_ratio(*dense, c), std::runtime_error);
}

// A target denser than the full friction gives, but loosening is impossible: a target above the
// full-friction void ratio is missed, reported in the result and refused with a message naming
// the RVE and the JSON path.
TEST(RveCompaction, MissedTargetStopsWithMessage) {
  auto reference = rve::Rve::generate(spec_with(R"({"confining_pressure": 1e5})"), MPI_COMM_WORLD,
                                      "full friction");
  const double target = rve::consolidate(*reference).final.void_ratio + 0.05;
  const rve::RveSpec spec = spec_with(R"({"confining_pressure": 1e5, "target_void_ratio": )" +
                                      std::to_string(target) + "}");
  auto loose = rve::Rve::generate(spec, MPI_COMM_WORLD, "too loose a target");
  const rve::ConsolidationResult c = rve::consolidate(*loose);
  EXPECT_FALSE(c.void_ratio_reached);
  EXPECT_NEAR(c.void_ratio_error, -0.05, 0.005);
  try {
    rve::require_void_ratio(*loose, c);
    ADD_FAILURE() << "a missed target passed";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("too loose a target"), std::string::npos) << message;
    EXPECT_NE(message.find("rve.preparation.target_void_ratio"), std::string::npos) << message;
  }
}

namespace {

//! The engine's DEM step, measured: all grains given one more velocity along x, the packing
//! run `steps` steps; momentum is conserved, so the grains' mass-weighted mean displacement
//! is their mean velocity times the elapsed time.
double measured_time_step(rve::Rve& rve, int steps) {
  dem::Engine& engine = rve.engine();
  engine.command("velocity all set 1e-3 0 0 sum yes units box");
  const rve::GrainState before = rve::gather_grains(engine);
  // The engine's own run: an RVE's update would take out the net momentum with its streaming.
  engine.command("run " + std::to_string(steps));
  const rve::GrainState after = rve::gather_grains(engine);
  const dem::Box box = engine.box();
  const Vec3 length = box.hi - box.lo;
  double momentum = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < before.x.size(); ++i) {
    Vec3 d = after.x[i] - before.x[i];
    const double wraps_y = std::round(d.y() / length.y());  // a y wrap shifts x by the tilt
    d.x() -= wraps_y * box.xy;
    d.x() -= std::round(d.x() / length.x()) * length.x();
    momentum += before.mass[i] * before.v[i].x();
    moved += before.mass[i] * d.x();
  }
  return moved / (momentum * steps);
}

}  // namespace

// A preparation at its own DEM step makes the packing the RVE's own step would not: the
// loading then runs at the RVE's step (docs/dem_work.md §11).
TEST(RvePreparation, OwnTimeStepPreparesAndTheRveLoadsAtItsOwn) {
  const std::string preparation = R"({"confining_pressure": 1e5})";
  const rve::RveSpec plain = spec_with(preparation);
  rve::RveSpec split = spec_with(R"({"confining_pressure": 1e5, "time_step_fraction": 0.1})");
  EXPECT_DOUBLE_EQ(plain.preparation.time_step, plain.time_step);
  EXPECT_DOUBLE_EQ(split.preparation.time_step, 0.1 * split.rayleigh_time_step);
  EXPECT_DOUBLE_EQ(split.time_step, 0.15 * split.rayleigh_time_step);

  // The same preparation step, whatever the loading one: the same packing, bit for bit.
  rve::RveSpec reference = spec_with(preparation);
  reference.time_step = split.preparation.time_step;
  reference.preparation.time_step = split.preparation.time_step;
  auto a = rve::Rve::generate(reference, MPI_COMM_WORLD, "prepared at 0.1");
  auto b = rve::Rve::generate(split, MPI_COMM_WORLD, "prepared at 0.1, loaded at 0.15");
  EXPECT_DOUBLE_EQ(b->time_step(), split.preparation.time_step);
  const rve::ConsolidationResult ca = rve::consolidate(*a);
  const rve::ConsolidationResult cb = rve::consolidate(*b);
  EXPECT_EQ(ca.steps, cb.steps);
  EXPECT_EQ(ca.final.void_ratio, cb.final.void_ratio);
  EXPECT_EQ(ca.final.stress, cb.final.stress);

  b->use_loading_time_step();
  EXPECT_DOUBLE_EQ(b->time_step(), split.time_step);
  EXPECT_NEAR(measured_time_step(*a, 200), reference.time_step, 1e-6 * reference.time_step);
  EXPECT_NEAR(measured_time_step(*b, 200), split.time_step, 1e-6 * split.time_step);
}
