#include "mpm/register.h"

namespace mpm_lig::mpm {

void register_analyses(AnalysisRegistry& /*registry*/) {}

}  // namespace mpm_lig::mpm
