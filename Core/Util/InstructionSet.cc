#include "Core/Util/InstructionSet.h"

#include <vector>

namespace anode {

namespace {

struct Extension {
  const char* name;
  bool onThisCpu;
};

// The extensions the compiler targets, widest first (__builtin_cpu_supports takes literals).
std::vector<Extension> targetedExtensions() {
  __builtin_cpu_init();
  std::vector<Extension> e;
#ifdef __AVX512F__
  e.push_back({"AVX-512", __builtin_cpu_supports("avx512f") != 0});
#endif
#ifdef __AVX2__
  e.push_back({"AVX2", __builtin_cpu_supports("avx2") != 0});
#endif
#ifdef __FMA__
  e.push_back({"FMA", __builtin_cpu_supports("fma") != 0});
#endif
#ifdef __AVX__
  if (e.empty()) e.push_back({"AVX", __builtin_cpu_supports("avx") != 0});
#endif
  return e;
}

std::string join(const std::vector<Extension>& extensions, bool missingOnly) {
  std::string s;
  for (const Extension& e : extensions)
    if (!missingOnly || !e.onThisCpu) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s;
}

}  // namespace

std::string instructionSet() {
  const std::string names = join(targetedExtensions(), false);
  return std::string(ANODE_SIMD) + " (" + (names.empty() ? "SSE2, baseline x86-64" : names) + ")";
}

std::string missingInstructions() {
  return join(targetedExtensions(), true);
}

}  // namespace anode
