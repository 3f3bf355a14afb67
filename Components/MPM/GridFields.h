// Nodal fields of one material on the background grid; cleared each step, never reallocated.
#pragma once

#include <vector>

#include "Core/Math/Types.h"

namespace anode {

struct GridFields {
  std::vector<double> mass;          // g.mass (Eq. 4)
  std::vector<Vec3> velocity;        // g.velocity: momentum during P2G, then velocity
  std::vector<Vec3> internalForce;   // g.internalforce
  std::vector<Vec3> velocityStar;    // g.velocity_star: after integration and BCs
  std::vector<Vec3> acceleration;    // g.acceleration

  void resize(int nodes) {
    mass.assign(nodes, 0.0);
    velocity.assign(nodes, Vec3::Zero());
    internalForce.assign(nodes, Vec3::Zero());
    velocityStar.assign(nodes, Vec3::Zero());
    acceleration.assign(nodes, Vec3::Zero());
  }
};

}  // namespace anode
