#include "core/test_hooks.h"

#include <cstdlib>

namespace mpm_lig {
namespace {

long environment_number(const char* name, long fallback) {
  const char* value = std::getenv(name);
  return value ? std::strtol(value, nullptr, 10) : fallback;
}

}  // namespace

TestHooks TestHooks::from_environment() {
  TestHooks hooks;
  hooks.kill_at_step = environment_number("MPM_LIG_KILL_AT_STEP", hooks.kill_at_step);
  hooks.term_at_step = environment_number("MPM_LIG_TERM_AT_STEP", hooks.term_at_step);
  hooks.term_at_packing = environment_number("MPM_LIG_TERM_AT_PACKING", hooks.term_at_packing);
  hooks.fault_point = environment_number("MPM_LIG_FAULT_POINT", hooks.fault_point);
  hooks.fault_update = environment_number("MPM_LIG_FAULT_UPDATE", hooks.fault_update);
  return hooks;
}

}  // namespace mpm_lig
