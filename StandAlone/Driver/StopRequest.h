// SIGTERM and SIGINT ask a run to stop: the time loop finishes its step, writes a checkpoint and
// returns, so `sus -restart` continues with nothing lost (SIGKILL still loses the work since the
// newest checkpoint).
#pragma once

namespace anode {

// Installs the handlers (from then on the two signals only set the request).
void catchStopSignals();
// True once SIGTERM or SIGINT has arrived.
bool stopRequested();

}  // namespace anode
