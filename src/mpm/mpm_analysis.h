#pragma once

#include <memory>

#include "core/analysis.h"
#include "materials/material.h"

namespace mpm_lig::mpm {

//! The "mpm" analysis for `root` (an explicit MPM run, checked, resumable), its materials
//! taken from `materials` (tests add their own).
std::unique_ptr<Analysis> make_analysis(const CaseNode& root,
                                        const materials::MaterialRegistry& materials);

}  // namespace mpm_lig::mpm
