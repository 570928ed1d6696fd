#include <string>

#include <gtest/gtest.h>

#include "core/case_error.h"
#include "core/case_node.h"
#include "materials/material.h"
#include "materials/plastic.h"

namespace mpm_lig::materials {
namespace {

//! Build the material in `{"materials": [<json>]}` as the MPM case reader does.
std::unique_ptr<Material> create(const std::string& material_json) {
  const CaseDocument doc = CaseDocument::parse("{\"materials\": [" + material_json + "]}");
  MaterialRegistry registry;
  register_materials(registry);
  const CaseNode node = doc.root().children("materials").at(0);
  auto material = registry.create(node, "type", node);
  doc.check_all_used();
  return material;
}

//! The JSON path of the CaseError that creating the material throws ("" if none).
std::string error_path(const std::string& material_json) {
  try {
    create(material_json);
  } catch (const CaseError& error) {
    return error.path();
  }
  return "";
}

const std::string kElastic = R"("density": 1800, "youngs_modulus": 2e7, "poisson_ratio": 0.3)";

TEST(MaterialCaseKeys, EachMaterialReadsItsKeys) {
  auto elastic = create(R"({"type": "linear_elastic", )" + kElastic + "}");
  EXPECT_EQ(elastic->type(), "linear_elastic");
  EXPECT_DOUBLE_EQ(elastic->density(), 1800.0);
  const double g = 2e7 / 2.6, lambda = 2e7 * 0.3 / (1.3 * 0.4);
  EXPECT_NEAR(elastic->wave_modulus(), lambda + 2.0 * g, 1e-6);

  auto vm = create(R"({"type": "von_mises", "yield_stress": 1e5, )" + kElastic + "}");
  EXPECT_DOUBLE_EQ(dynamic_cast<VonMises&>(*vm).yield_stress(), 1e5);
  EXPECT_EQ(vm->state_names().at(0), "plastic_strain");

  auto tresca = create(R"({"type": "tresca", "undrained_strength": 3e4, )" + kElastic + "}");
  EXPECT_DOUBLE_EQ(dynamic_cast<MohrCoulomb&>(*tresca).strength().cohesion, 3e4);
  EXPECT_DOUBLE_EQ(dynamic_cast<MohrCoulomb&>(*tresca).strength().friction, 0.0);

  auto mc = create(R"({"type": "mohr_coulomb", "cohesion": 1e3, "friction_deg": 30,
                       "dilatancy_deg": 30, "tension_cutoff": 500, )" +
                   kElastic + "}");
  const MohrCoulombStrength& s = dynamic_cast<MohrCoulomb&>(*mc).strength();
  EXPECT_NEAR(s.friction, s.dilatancy, 1e-15);
  EXPECT_DOUBLE_EQ(s.tension_cutoff, 500.0);

  auto soft = create(R"({"type": "mohr_coulomb", "cohesion": 0, "friction_deg": 31,
                         "dilatancy_deg": 10, "softening": {"residual_friction_deg": 20,
                         "plastic_strain": 0.1}, )" +
                     kElastic + "}");
  const auto& softening = dynamic_cast<MohrCoulomb&>(*soft);
  EXPECT_NEAR(softening.strength(0.05).friction, 25.5 * kDegree, 1e-12);
  EXPECT_NEAR(softening.strength(0.05).dilatancy, 5.0 * kDegree, 1e-12);  // ψ_r default 0
  EXPECT_NEAR(softening.strength(1.0).friction, 20.0 * kDegree, 1e-12);
}

TEST(MaterialCaseKeys, BadValuesNameTheirJsonPath) {
  const std::string mc = R"({"type": "mohr_coulomb", "cohesion": 1e3, )";
  EXPECT_EQ(error_path(R"({"type": "elastic", )" + kElastic + "}"), "materials[0].type");
  EXPECT_EQ(error_path(R"({"type": "linear_elastic", "youngs_modulus": 1e7,
                           "poisson_ratio": 0.3})"),
            "materials[0].density");
  EXPECT_EQ(error_path(R"({"type": "linear_elastic", "density": 1800, "youngs_modulus": -1,
                           "poisson_ratio": 0.3})"),
            "materials[0].youngs_modulus");
  for (const char* nu : {"0.5", "-1", "0.7"}) {
    EXPECT_EQ(error_path(std::string(R"({"type": "linear_elastic", "density": 1800,
                           "youngs_modulus": 1e7, "poisson_ratio": )") +
                         nu + "}"),
              "materials[0].poisson_ratio")
        << nu;
  }
  EXPECT_EQ(error_path(R"({"type": "von_mises", "yield_stress": 0, )" + kElastic + "}"),
            "materials[0].yield_stress");
  // G = 2e7 / 2.6 for kElastic: H must stay below 3G ≈ 2.3e7.
  EXPECT_EQ(error_path(R"({"type": "von_mises", "yield_stress": 1e5, "softening_modulus": 3e7, )" +
                       kElastic + "}"),
            "materials[0].softening_modulus");
  EXPECT_EQ(error_path(R"({"type": "von_mises", "yield_stress": 1e5,
                           "softening_modulus": 1e6, "residual_yield_stress": 2e5, )" +
                       kElastic + "}"),
            "materials[0].residual_yield_stress");
  EXPECT_EQ(error_path(R"({"type": "von_mises", "yield_stress": 1e5,
                           "residual_yield_stress": 2e4, )" +
                       kElastic + "}"),
            "materials[0].residual_yield_stress");
  EXPECT_EQ(error_path(R"({"type": "tresca", )" + kElastic + "}"),
            "materials[0].undrained_strength");
  EXPECT_EQ(error_path(mc + R"("friction_deg": 90, )" + kElastic + "}"),
            "materials[0].friction_deg");
  EXPECT_EQ(error_path(mc + R"("friction_deg": 0, )" + kElastic + "}"),
            "materials[0].friction_deg");
  EXPECT_EQ(error_path(mc + R"("friction_deg": 30, "dilatancy_deg": 31, )" + kElastic + "}"),
            "materials[0].dilatancy_deg");
  EXPECT_EQ(error_path(mc + R"("friction_deg": 30, "tension_cutoff": 2000, )" + kElastic + "}"),
            "materials[0].tension_cutoff");  // above the apex c cot φ = 1732 Pa
  EXPECT_EQ(error_path(mc + R"("friction_deg": "30", )" + kElastic + "}"),
            "materials[0].friction_deg");
  EXPECT_EQ(error_path(mc + R"("frction_deg": 30, "friction_deg": 30, )" + kElastic + "}"),
            "materials[0].frction_deg");
  const std::string soft = mc + R"("friction_deg": 30, "dilatancy_deg": 8, "softening": )";
  EXPECT_EQ(error_path(soft + R"({"residual_friction_deg": 31, "plastic_strain": 0.1}, )" +
                       kElastic + "}"),
            "materials[0].softening.residual_friction_deg");  // above the peak
  EXPECT_EQ(error_path(soft + R"({"residual_friction_deg": 0, "plastic_strain": 0.1}, )" +
                       kElastic + "}"),
            "materials[0].softening.residual_friction_deg");
  EXPECT_EQ(error_path(soft + R"({"residual_friction_deg": 20, "residual_dilatancy_deg": 9,
                                  "plastic_strain": 0.1}, )" +
                       kElastic + "}"),
            "materials[0].softening.residual_dilatancy_deg");  // above the peak ψ
  EXPECT_EQ(error_path(soft + R"({"residual_friction_deg": 20}, )" + kElastic + "}"),
            "materials[0].softening.plastic_strain");
  EXPECT_EQ(error_path(soft + R"({"residual_friction_deg": 20, "plastic_strain": 0.1,
                                  "plastic_strian": 1}, )" +
                       kElastic + "}"),
            "materials[0].softening.plastic_strian");
  EXPECT_EQ(error_path(soft + "20, " + kElastic + "}"), "materials[0].softening");
  EXPECT_EQ(error_path(mc + R"("friction_deg": 30, )" + kElastic + "}"), "");
  const std::string dp = R"({"type": "drucker_prager", "cohesion": 1e3, "friction_deg": 30, )";
  EXPECT_EQ(error_path(dp + kElastic + "}"), "materials[0].match");
  EXPECT_EQ(error_path(dp + R"("match": "plane", )" + kElastic + "}"), "materials[0].match");
  EXPECT_EQ(error_path(dp + R"("match": "plane_strain", )" + kElastic + "}"), "");
}

}  // namespace
}  // namespace mpm_lig::materials
