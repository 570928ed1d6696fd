#include "materials/material.h"

namespace mpm_lig::materials {

void register_materials(MaterialRegistry& /*registry*/) {}

}  // namespace mpm_lig::materials
