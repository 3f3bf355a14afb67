// What the step under way is doing, for the progress line of a long step (the driver prints it
// at least every 10 s while a step runs longer): the long phases name themselves as they go. Level
// 0 is the step's phase ("Newton iteration", "diffusion sub-step", "RKL2 stage"), level 1 a loop
// within it ("Krylov iteration"). Relaxed atomic stores: nothing the step computes depends on it.
#pragma once

#include <string>

namespace anode {

// The phase at `level` (0 or 1) is now `what` (a string literal) number `count`; level 0 clears
// level 1.
void noteStepActivity(int level, const char* what, long count);
// Forgets the activity (a step ends).
void clearStepActivity();
// "Newton iteration 4, Krylov iteration 230"; "" when nothing is noted.
std::string describeStepActivity();

}  // namespace anode
