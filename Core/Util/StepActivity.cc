#include "Core/Util/StepActivity.h"

#include <atomic>

namespace anode {

namespace {

std::atomic<const char*> activity[2] = {nullptr, nullptr};
std::atomic<long> counts[2] = {0, 0};

}  // namespace

void noteStepActivity(int level, const char* what, long count) {
  counts[level].store(count, std::memory_order_relaxed);
  activity[level].store(what, std::memory_order_relaxed);
  if (level == 0) activity[1].store(nullptr, std::memory_order_relaxed);
}

void clearStepActivity() {
  for (auto& a : activity) a.store(nullptr, std::memory_order_relaxed);
}

std::string describeStepActivity() {
  std::string text;
  for (int level = 0; level < 2; ++level) {
    const char* what = activity[level].load(std::memory_order_relaxed);
    if (!what) continue;
    if (!text.empty()) text += ", ";
    text += what + (" " + std::to_string(counts[level].load(std::memory_order_relaxed)));
  }
  return text;
}

}  // namespace anode
