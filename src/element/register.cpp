#include "element/register.h"

namespace mpm_lig::element {

void register_analyses(AnalysisRegistry& /*registry*/) {}

}  // namespace mpm_lig::element
