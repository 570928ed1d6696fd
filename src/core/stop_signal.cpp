#include "core/stop_signal.h"

#include <csignal>

namespace mpm_lig {
namespace {

volatile std::sig_atomic_t g_stop_received = 0;

extern "C" void note_stop_signal(int /*signal*/) {
  g_stop_received = 1;
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = note_stop_signal;
  sigemptyset(&action.sa_mask);
  // Restart interrupted system calls: a write in progress finishes, the run stops after it.
  action.sa_flags = SA_RESTART;
  for (const int signal : {SIGTERM, SIGINT, SIGHUP})
    sigaction(signal, &action, nullptr);
}

bool stop_signal_received() {
  return g_stop_received != 0;
}

bool stop_requested(MPI_Comm comm) {
  int local = stop_signal_received() ? 1 : 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

}  // namespace mpm_lig
