#include "core/test_hooks.h"

#include <csignal>
#include <cstdlib>

namespace mpm_lig {
namespace {

long environment_number(const char* name, long fallback) {
  const char* value = std::getenv(name);
  return value ? std::strtol(value, nullptr, 10) : fallback;
}

}  // namespace

void TestHooks::at(Moment moment, long index, int rank) const {
  switch (moment) {
    case Moment::step_recorded:
      if (rank == 0 && index == term_at_step)
        std::raise(SIGTERM);  // as a signal arriving during that step
      return;
    case Moment::step_finished:
      if (rank == 0 && index == kill_at_step)
        std::raise(SIGKILL);
      return;
    case Moment::packing_started:
      if (index == term_at_packing)
        std::raise(SIGTERM);  // as a signal in the middle of the preparation
      return;
  }
}

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
