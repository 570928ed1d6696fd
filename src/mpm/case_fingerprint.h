#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace mpm_lig::mpm {

//! Keys of a case that may change between a checkpoint and its resume: when and how often the
//! run writes, and when it ends. Any other difference changes the physics or the files a
//! resume continues, so the resume is refused. `*` stands for any array index.
const std::vector<std::string>& keys_safe_to_change_on_resume();

//! The keys (JSON paths like `materials[0].rve.seed`) where `saved` and `now` differ, except
//! keys_safe_to_change_on_resume(); a key present in one only counts as a difference.
std::vector<std::string> changed_case_keys(const nlohmann::json& saved, const nlohmann::json& now);

}  // namespace mpm_lig::mpm
