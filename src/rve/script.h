#pragma once

#include <map>
#include <set>
#include <string>

namespace mpm_lig::rve {

//! Text of an engine input template from lmp_inputs/ (compiled into the binary), e.g.
//! `engine_template("liggghts", "material.in")`. Throws std::out_of_range if there is none.
const std::string& engine_template(const std::string& engine, const std::string& name);

//! Fill a template: `${name}` becomes `values.at(name)`; a block between `#@if FLAG` and
//! `#@endif` is kept only when FLAG is in `flags`. An unknown `${name}` throws
//! std::invalid_argument (a template and its caller must agree).
std::string render_template(const std::string& text,
                            const std::map<std::string, std::string>& values,
                            const std::set<std::string>& flags);

}  // namespace mpm_lig::rve
