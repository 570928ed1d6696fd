// The engine input holds only the contact effects a case asks for: rolling resistance and
// cohesion appear in the contact law (and their material constants) only when the case's
// rve.contact gives them, for both engines; 2D adds the in-plane constraint, 3D does not.
#include <gtest/gtest.h>

#include <string>

#include "rve/engine_input.h"
#include "test_rve_spec.h"

using namespace mpm_lig;

namespace {

std::string contact_law(const std::string& engine, const nlohmann::json& contact_extra) {
  nlohmann::json rve = test::small_rve_json();
  rve["engine"] = engine;
  for (auto it = contact_extra.begin(); it != contact_extra.end(); ++it)
    rve["contact"][it.key()] = it.value();
  return rve::material_input(test::parse_rve(rve), 0.5);
}

}  // namespace

TEST(EngineInput, RollingAndCohesionOnlyWhenAsked) {
  for (const std::string engine : {"liggghts", "lammps"}) {
    const std::string plain = contact_law(engine, nlohmann::json::object());
    EXPECT_EQ(plain.find("rolling"), std::string::npos) << engine << ":\n" << plain;
    EXPECT_EQ(plain.find("Rolling"), std::string::npos) << engine << ":\n" << plain;
    EXPECT_EQ(plain.find("cohesion"), std::string::npos) << engine << ":\n" << plain;
    const std::string rolling = contact_law(engine, {{"rolling_friction", 0.1}});
    EXPECT_NE(rolling.find("rolling"), std::string::npos) << engine << ":\n" << rolling;
    EXPECT_EQ(rolling.find("cohesion"), std::string::npos) << engine << ":\n" << rolling;
  }
  const std::string cohesive = contact_law("liggghts", {{"cohesion_energy_density", 1e5}});
  EXPECT_NE(cohesive.find("cohesion sjkr"), std::string::npos) << cohesive;
  EXPECT_NE(cohesive.find("cohesionEnergyDensity"), std::string::npos) << cohesive;
  EXPECT_EQ(cohesive.find("rolling"), std::string::npos) << cohesive;
}

TEST(EngineInput, PlaneConstraintOnlyIn2d) {
  nlohmann::json rve = test::small_rve_json();
  rve["engine"] = "liggghts";
  EXPECT_NE(rve::dynamics_input(test::parse_rve(rve), 1e-6).find("enforce2d"), std::string::npos);
  rve["dimension"] = 3;
  EXPECT_EQ(rve::dynamics_input(test::parse_rve(rve), 1e-6).find("enforce2d"), std::string::npos);
}
