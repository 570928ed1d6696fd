#include "coupling/rve_state_fields.h"

#include <algorithm>

namespace mpm_lig::coupling {

void pack_state(const rve::Rve::State& s, double* v) {
  rve::Rve::State copy = s;
  for (const RveStateField& f : kRveStateFields)
    v = std::copy_n(f.at(copy), f.width, v);
}

rve::Rve::State unpack_state(const double* v) {
  rve::Rve::State s;
  for (const RveStateField& f : kRveStateFields) {
    std::copy_n(v, f.width, f.at(s));
    v += f.width;
  }
  return s;
}

}  // namespace mpm_lig::coupling
