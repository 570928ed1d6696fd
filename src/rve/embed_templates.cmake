# Writes OUTPUT: a C++ file holding every engine input template of lmp_inputs/ as a string,
# so that the binary does not depend on the source tree at run time.
file(GLOB_RECURSE templates RELATIVE ${INPUT_DIR} ${INPUT_DIR}/*.in)
list(SORT templates)
set(body "")
foreach(t ${templates})
  file(READ ${INPUT_DIR}/${t} text)
  string(APPEND body "      {\"${t}\", R\"lmpin(${text})lmpin\"},\n")
endforeach()
file(WRITE ${OUTPUT}.tmp "// Generated from lmp_inputs/ by embed_templates.cmake: do not edit.
#include \"rve/script.h\"

#include <map>

namespace mpm_lig::rve {

const std::string& engine_template(const std::string& engine, const std::string& name) {
  static const std::map<std::string, std::string> templates = {
${body}  };
  return templates.at(engine + \"/\" + name);
}

}  // namespace mpm_lig::rve
")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUTPUT}.tmp ${OUTPUT})
