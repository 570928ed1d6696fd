#pragma once

#include <string>

#include "materials/continuum.h"

namespace mpm_lig::materials {

//! "linear_elastic": isotropic, hypoelastic in the Jaumann rate (Hughes–Winget update).
class LinearElastic : public ContinuumMaterial {
 public:
  using ContinuumMaterial::ContinuumMaterial;
  std::string type() const override { return "linear_elastic"; }
};

}  // namespace mpm_lig::materials
