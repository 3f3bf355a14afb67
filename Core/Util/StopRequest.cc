#include "Core/Util/StopRequest.h"

#include <csignal>

namespace anode {

namespace {

volatile std::sig_atomic_t requested = 0;

extern "C" void requestStop(int) {
  requested = 1;
}

}  // namespace

void catchStopSignals() {
  std::signal(SIGTERM, requestStop);
  std::signal(SIGINT, requestStop);
  std::signal(SIGUSR1, requestStop);
}

bool stopRequested() {
  return requested != 0;
}

}  // namespace anode
