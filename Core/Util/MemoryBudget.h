// How much memory a run may plan for. Setup refuses, with an InputError at the tag responsible,
// a grid or a particle count whose arrays alone would not fit, instead of failing an allocation
// (or exhausting the machine) later. The default is the machine's physical memory.
#pragma once

#include <cstddef>
#include <string>

namespace anode {

size_t memoryBudget();
// 0 restores the default. Tests and the input fuzzer lower it so absurd sizes fail fast.
void setMemoryBudget(size_t bytes);
// "the memory budget of 24.1 GB (the machine's physical memory)", for messages.
std::string describeMemoryBudget();
// "1.5 GB", "320 MB", ...
std::string formatBytes(double bytes);
// A node or particle count to 4 digits: "950", "1.266e+04", ...
std::string formatCount(double n);

}  // namespace anode
