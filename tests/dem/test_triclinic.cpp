// LIGGGHTS 3.8 loses periodic ghosts in triclinic boxes unless the adapter corrects the
// Domain's lamda-box size (liggghts_engine.cpp). This test shows the defect is still in the
// library (without the correction) and that the correction removes it.
#include <gtest/gtest.h>

#include "dem/engine_module.h"
#include "dem/guarded_engine.h"
#include "dem_scripts.h"

namespace mpm_lig::dem::test {
namespace {

struct PeriodicHealth {
  long ghosts = 0;
  long atoms_before = 0;
  long atoms_after = 0;
};

//! A sheared periodic packing whose grains drift across the box faces.
PeriodicHealth run_triclinic_packing(bool skip_correction) {
  const Material material;
  const int n = 4;
  const double spacing = 0.01;
  Box box;
  box.hi = Vec3::Constant(n * spacing);
  box.xy = 0.2 * spacing;
  box.xz = 0.1 * spacing;
  box.yz = -0.1 * spacing;
  detail::ModuleOptions module;
  module.skip_triclinic_correction = skip_correction;
  auto engine = detail::create_engine("liggghts", MPI_COMM_SELF, {"triclinic test", ""}, module);
  engine->commands(setup_script("liggghts", box, true, material));
  engine->commands(grains_script(jittered_packing(n, spacing, 11u), material));
  engine->commands(dynamics_script(1e-6, "p"));
  engine->command("thermo_modify lost ignore");  // so that the defect can be observed
  engine->command("velocity all set 6.0 4.0 2.0");
  PeriodicHealth health;
  health.atoms_before = engine->atom_count();
  engine->command("run 1000");
  health.ghosts = dynamic_cast<detail::GuardedEngine&>(*engine).ghost_count();
  health.atoms_after = engine->atom_count();
  return health;
}

TEST(LiggghtsTriclinic, DefectIsInTheLibrary) {
  const PeriodicHealth health = run_triclinic_packing(true);
  EXPECT_EQ(health.ghosts, 0);
  EXPECT_LT(health.atoms_after, health.atoms_before) << "no atom lost without the correction";
}

TEST(LiggghtsTriclinic, CorrectionKeepsGhostsAndAtoms) {
  const PeriodicHealth health = run_triclinic_packing(false);
  EXPECT_GT(health.ghosts, 0);
  EXPECT_EQ(health.atoms_after, health.atoms_before);
}

}  // namespace
}  // namespace mpm_lig::dem::test
