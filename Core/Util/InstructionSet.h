// The instruction set this build targets (CMake's ANODE_SIMD, docs/performance.md) and whether
// the CPU running it has it.
#pragma once

#include <string>

namespace anode {

// E.g. "native (AVX-512, AVX2, FMA)": the ANODE_SIMD choice and the vector extensions the
// compiler was allowed to use.
std::string instructionSet();
// The extensions the build uses that this CPU lacks ("" if none): a run would die of an illegal
// instruction.
std::string missingInstructions();

}  // namespace anode
