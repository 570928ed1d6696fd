#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace mpm_lig::io {

//! Write `summary` as pretty JSON to `filename` (written to a temporary name, then renamed,
//! so a reader never sees half a file).
void write_json(const std::string& filename, const nlohmann::json& summary);

}  // namespace mpm_lig::io
