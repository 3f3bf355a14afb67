#include "Core/ProblemSpec/UpsText.h"

#include <cstdio>

namespace anode {

std::string upsNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string upsVector(double x, double y, double z) {
  return "[" + upsNumber(x) + "," + upsNumber(y) + "," + upsNumber(z) + "]";
}

}  // namespace anode
