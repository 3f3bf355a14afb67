// Nodal fields of one material on the background grid (mechanics; the diffusion subcomponent
// keeps its own: ReactiveFlow/DiffusionGridFields.h); cleared each step, never reallocated.
// Each keeps one meaning for the whole step.
#pragma once

#include <algorithm>
#include <vector>

#include "Core/Math/Types.h"

namespace anode {

struct GridFields {
  std::vector<double> mass;         // g.mass = sum m S (Eq. 4)
  std::vector<Vec3> momentum;       // sum m v S
  std::vector<Vec3> internalForce;  // g.internalforce = -sum V sigma grad S
  std::vector<Vec3> velocity;       // g.velocity = momentum / mass, after contact
  std::vector<Vec3> velocityStar;   // g.velocity_star: after integration and BCs
  std::vector<Vec3> acceleration;   // g.acceleration = (velocity_star - velocity) / dt

  void resize(int nodes) {
    mass.assign(nodes, 0.0);
    for (auto* f : {&momentum, &internalForce, &velocity, &velocityStar, &acceleration})
      f->assign(nodes, Vec3::Zero());
  }
  // Zeroes every field on nodes [begin, end).
  void clearAll(long begin, long end) {
    std::fill(mass.begin() + begin, mass.begin() + end, 0.0);
    for (auto* f : {&momentum, &internalForce, &velocity, &velocityStar, &acceleration})
      std::fill(f->begin() + begin, f->begin() + end, Vec3::Zero());
  }
};

}  // namespace anode
