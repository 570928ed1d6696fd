#include "coupling/register.h"

#include "coupling/dem_rve_material.h"

namespace mpm_lig::coupling {

void register_materials(materials::MaterialRegistry& registry) {
  registry.add("dem_rve", [](const CaseNode& node) -> std::unique_ptr<materials::Material> {
    return std::make_unique<DemRveMaterial>(node);
  });
  registry.add_statistics(dem_statistics(DemCost{}));
}

}  // namespace mpm_lig::coupling
