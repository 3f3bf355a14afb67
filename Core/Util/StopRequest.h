// SIGTERM, SIGINT and SIGUSR1 ask a run to stop: the time loop ends after the step under way,
// or, in a quasi-static step's long phases (the diffusion pass's sub-steps and stages, Newton's
// iterations), drops that step (collective::stopIfRequested); then it writes a checkpoint of the
// last completed step and returns, so `sus -restart` continues with nothing lost (SIGKILL still
// loses the work since the newest checkpoint). SIGUSR1 is the one for mpirun: Open MPI passes it
// on to every rank and does nothing else, while a SIGTERM or SIGINT to mpirun makes it kill the
// ranks (SIGTERM, then SIGKILL a second later).
#pragma once

namespace anode {

// Installs the handlers (from then on the three signals only set the request).
void catchStopSignals();
// True once SIGTERM, SIGINT or SIGUSR1 has arrived.
bool stopRequested();

}  // namespace anode
