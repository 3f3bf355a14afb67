// Implicit dynamics (<dynamic>true, ImpMPM's default; Guilkey and Weiss 2003): Newmark's
// trapezoidal rule, beta = 1/4 and gamma = 1/2, on the grid. With the nodal velocity v and
// acceleration a of the step's start (interpolated from the particles) and the step's
// displacement increment u, the acceleration at the step's end is
//   a' = 4/dt^2 (u - v dt) - a,
// and the velocity v' = v + dt/2 (a + a'). Newton then balances m a' with the forces: the residual
// gains -m a', the Jacobian 4 m/dt^2 on the diagonal. The particles take x += sum S u,
// v_p += dt/2 (a_p + sum S a') and a_p = sum S a' (ImpMPM's update).
#pragma once

#include "Core/Math/Types.h"

namespace anode {

// a' of a node (Newmark, beta = 1/4).
inline Vec3 newmarkAcceleration(const Vec3& u, const Vec3& velocity, const Vec3& acceleration,
                                double dt) {
  return 4 / (dt * dt) * (u - velocity * dt) - acceleration;
}

// d(m a')/du = this times m (the inertia's part of the Jacobian).
inline double newmarkStiffnessPerMass(double dt) {
  return 4 / (dt * dt);
}

}  // namespace anode
