// Numbers written into input (.ups) and figure files so that reading them back gives the same
// doubles.
#pragma once

#include <string>

namespace anode {

// Enough digits to read back the same double (%.17g).
std::string upsNumber(double v);
// "[x,y,z]", each with upsNumber.
std::string upsVector(double x, double y, double z);

}  // namespace anode
