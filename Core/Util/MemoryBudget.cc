#include "Core/Util/MemoryBudget.h"

#include <unistd.h>

#include <cstdio>

namespace anode {

namespace {

size_t budget = 0;

size_t physicalMemory() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<size_t>(pages) * static_cast<size_t>(size)
                               : size_t(24) << 30;
}

}  // namespace

size_t memoryBudget() {
  return budget > 0 ? budget : physicalMemory();
}

void setMemoryBudget(size_t bytes) {
  budget = bytes;
}

std::string describeMemoryBudget() {
  return "the memory budget of " + formatBytes(static_cast<double>(memoryBudget())) +
         (budget > 0 ? std::string(" (set by the caller)")
                     : std::string(" (the machine's physical memory)"));
}

std::string formatBytes(double bytes) {
  char s[32];
  if (bytes >= 1e9)
    std::snprintf(s, sizeof s, "%.3g GB", bytes / 1e9);
  else
    std::snprintf(s, sizeof s, "%.3g MB", bytes / 1e6);
  return s;
}

std::string formatCount(double n) {
  char s[32];
  std::snprintf(s, sizeof s, "%.4g", n);
  return s;
}

}  // namespace anode
