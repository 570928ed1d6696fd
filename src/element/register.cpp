#include "element/register.h"

#include "element/element_analysis.h"

namespace mpm_lig::element {

void register_analyses(AnalysisRegistry& registry) {
  registry.add("element_test", make_element_test);
}

}  // namespace mpm_lig::element
