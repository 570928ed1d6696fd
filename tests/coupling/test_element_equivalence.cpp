// One material point in one cell, every node's velocity prescribed (a homogeneous motion
// v = L x with spin): the dem_rve point must give exactly the stresses of a clone of its
// packing driven directly along the same increments (what the element-test tool does).
#include <filesystem>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <mpi.h>
#include <nlohmann/json.hpp>

#include "coupling/dem_rve_material.h"
#include "coupling/register.h"
#include "mpm/driver.h"

namespace mpm_lig::coupling {
namespace {

constexpr double kCell = 0.1;
constexpr double kTimeStep = 1e-3;
constexpr int kSteps = 8;

//! The velocity gradient of the motion (spin included): strain increments of about 1e-4.
Eigen::Matrix2d velocity_gradient() {
  Eigen::Matrix2d L;
  L << 0.05, 0.12, -0.02, -0.1;
  return L;
}

nlohmann::json velocity_bc(double x, double y, int axis, double v) {
  return {{"type", "velocity"},
          {"direction", axis == 0 ? "x" : "y"},
          {"velocity", v},
          {"nodes", {{"box", {{"min", {x, y}}, {"max", {x, y}}}}}}};
}

nlohmann::json one_point_case() {
  nlohmann::json c = {
      {"dimension", 2},
      {"analysis",
       {{"type", "mpm"}, {"time_step", {{"fixed", kTimeStep}}}, {"end", {{"steps", kSteps}}}}},
      {"mesh", {{"origin", {0, 0}}, {"size", {kCell, kCell}}, {"cells", {1, 1}}}},
      {"materials",
       {{{"id", 0},
         {"type", "dem_rve"},
         {"rve",
          {{"dimension", 2},
           {"grains", 60},
           {"radius", {{"min", 0.003}, {"max", 0.007}}},
           {"density", 2650},
           {"seed", 5},
           {"contact",
            {{"youngs_modulus", 7e8},
             {"poisson_ratio", 0.3},
             {"friction_deg", 26.6},
             {"damping_ratio", 0.1}}},
           {"time_step_fraction", 0.15},
           {"preparation", {{"confining_pressure", 1e5}}},
           {"substeps", {{"inertial_number", 1e-3}, {"min", 20}}}}}}}},
      {"bodies",
       {{{"material", 0},
         {"box", {{"min", {0, 0}}, {"max", {kCell, kCell}}}},
         {"points_per_cell", 1}}}}};
  const Eigen::Matrix2d L = velocity_gradient();
  nlohmann::json bcs = nlohmann::json::array();
  for (const double x : {0.0, kCell}) {
    for (const double y : {0.0, kCell}) {
      const Eigen::Vector2d v = L * Eigen::Vector2d(x, y);
      for (int axis = 0; axis < 2; ++axis)
        bcs.push_back(velocity_bc(x, y, axis, v[axis]));
    }
  }
  c["boundary_conditions"] = bcs;
  return c;
}

TEST(DemRveCoupling, OnePointEqualsElementTestOnAClone) {
  const std::string dir = std::string(MPM_LIG_BINARY_DIR) + "/coupling_element_equivalence";
  std::filesystem::remove_all(dir);
  const auto document = CaseDocument::parse(one_point_case().dump());
  document.root().child("analysis").choice("type", {"mpm"});
  materials::MaterialRegistry registry;
  coupling::register_materials(registry);
  mpm::MpmProblem c = mpm::read_case(document.root(), registry);
  document.check_all_used();
  mpm::prepare_materials(c, MPI_COMM_SELF, dir);
  const auto& material = dynamic_cast<const DemRveMaterial&>(*c.materials[0]);
  const Packing packing = material.packings().at(0);
  const rve::RveSpec spec = material.spec();

  std::vector<Mat3> increments, stresses;
  mpm::run_case<2>(std::move(c), "", [&](const mpm::Solver<2>& s) {
    ASSERT_EQ(s.particles().size(), 1u);
    increments.push_back(s.increments()[0]);
    stresses.push_back(s.particles().stress[0]);
  });
  ASSERT_EQ(static_cast<int>(increments.size()), kSteps);

  // The motion is homogeneous, so the point receives the midpoint increment of L dt exactly
  // (to round-off): dF = (I - L dt/2)^-1 (I + L dt/2).
  const Eigen::Matrix2d half = 0.5 * kTimeStep * velocity_gradient();
  Mat3 expected = Mat3::Identity();
  expected.topLeftCorner<2, 2>() =
      (Eigen::Matrix2d::Identity() - half).inverse() * (Eigen::Matrix2d::Identity() + half);
  for (const Mat3& dF : increments)
    EXPECT_LT((dF - expected).cwiseAbs().maxCoeff(), 1e-14);

  const double p0 = -packing.stress.trace() / 3.0;
  ASSERT_GT(p0, 5e4);
  auto clone = rve::Rve::from_restart(spec, packing.restart_file, MPI_COMM_SELF, "clone");
  double largest_change = 0.0;
  for (std::size_t k = 0; k < increments.size(); ++k) {
    clone->deform(increments[k]);
    const Mat3 direct = clone->stress();
    EXPECT_LE((direct - stresses[k]).cwiseAbs().maxCoeff(), 1e-12 * p0) << "increment " << k;
    largest_change = std::max(largest_change, (direct - packing.stress).cwiseAbs().maxCoeff());
  }
  // The path must load the packing measurably, or the comparison proves nothing.
  EXPECT_GT(largest_change, 0.02 * p0);
}

}  // namespace
}  // namespace mpm_lig::coupling
