// Small fixed-size tensor types used everywhere (Eigen; no hand-written 3x3 algebra).
#pragma once

#include <Eigen/Dense>

namespace anode {

using Vec3 = Eigen::Vector3d;
using Vec3i = Eigen::Vector3i;
using Mat3 = Eigen::Matrix3d;
using Mat9 = Eigen::Matrix<double, 9, 9>;  // a tangent dP/dH, index 3 a + d for (a, d)

}  // namespace anode
