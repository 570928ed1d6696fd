#pragma once

#include <string>

#include "rve/packing.h"
#include "rve/spec.h"

namespace mpm_lig::rve {

//! Exact text of a number for an engine command (17 significant digits).
std::string fmt(double value);

//! Engine input built from the templates in lmp_inputs/<engine>/ for one RVE.
//! Each piece contains only the effects `spec` asks for.
std::string setup_input(const RveSpec& spec, const Packing& packing);
std::string restart_input(const RveSpec& spec, const std::string& restart_file);
//! The contact law; `friction` overrides the spec's (compaction towards a target void ratio).
std::string material_input(const RveSpec& spec, double friction);
std::string dynamics_input(const RveSpec& spec, double time_step);

//! Neighbour skin distance used for the RVE [m].
double neighbour_skin(const RveSpec& spec);

}  // namespace mpm_lig::rve
