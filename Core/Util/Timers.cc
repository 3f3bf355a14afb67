#include "Core/Util/Timers.h"

namespace anode {

int TaskTimers::task(const std::string& name) {
  for (size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return static_cast<int>(i);
  names_.push_back(name);
  seconds_.push_back(0.0);
  return static_cast<int>(names_.size() - 1);
}

}  // namespace anode
