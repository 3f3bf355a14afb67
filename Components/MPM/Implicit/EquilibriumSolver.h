// Newton's method for the equilibrium of one quasi-static step on the grid (DESIGN.md §4b, step
// 3; docs/quasi-static.md): the unknowns are the displacement increments of the nodes the
// particles reach, one set per velocity field (materials in single_velocity contact share one,
// with null contact each body has its own); the residual is the external force (gravity) minus
// the internal force of the trial stresses; the Jacobian is assembled from the particles'
// algorithmic tangents; Symmetric and Velocity faces fix components. ImpMPM's convergence test.
#pragma once

#include <string>
#include <vector>

#include "Components/MPM/Implicit/BlockMatrix.h"
#include "Components/MPM/ImplicitOptions.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Core/Grid/Grid.h"
#include "Core/Util/Timers.h"

namespace anode {

// What one step's equilibrium is solved for.
struct EquilibriumProblem {
  const Grid& grid;
  std::vector<MPMMaterial>& materials;
  const std::vector<InterpolationWeights>& weights;  // per material, start-of-step
  std::vector<int> fieldOf;                          // material -> velocity field
  // Per field and node: the mass (sum m S) and the prescribed displacement increment of each
  // component (NaN where free).
  std::vector<std::vector<double>> mass;
  std::vector<std::vector<Vec3>> prescribed;
  Vec3 gravity;
  // Per material: the particles' concentration change over the step (the swelling the stress
  // update sees), or null.
  std::vector<const double*> concentrationChange;
};

// How Newton went in one attempt at a step.
struct NewtonReport {
  bool converged = false;
  int iterations = 0, krylovIterations = 0;
  // Per iteration: |du|^2 / max, du.r / first (ImpMPM's two ratios).
  std::vector<std::pair<double, double>> ratios;
  std::string failure;  // why it did not converge
};

class EquilibriumSolver {
 public:
  // Task timers: assembly (trial stresses, tangents, forces), linear solve.
  void useTimers(TaskTimers& timers);
  // Newton for the step of length dt; on success displacement(f) holds the converged nodal
  // increments of field f (by node).
  NewtonReport solve(const EquilibriumProblem& problem, double dt, const ImplicitOptions& options);
  const std::vector<Vec3>& displacement(int field) const { return u_[field]; }

 private:
  // The unknown nodes (block rows) and the pattern of their couplings, from the weights.
  void numberUnknowns(const EquilibriumProblem& problem);
  // K and the residual r = f_ext - f_int at the current u (fixed components of r zeroed).
  // `stabilization`: epsilon of Implicit/HourglassStabilization.h. Without the tangent: the
  // residual only (the line search's trials).
  void assemble(const EquilibriumProblem& problem, double dt, double stabilization,
                bool withTangent);
  // u += scale du (du by block row).
  void addToDisplacement(const std::vector<double>& du, double scale);
  // Newton's update u += step du with the line search's step; `residualNorm` is |r|^2 at u.
  void takeStep(const EquilibriumProblem& problem, double dt, double stabilization,
                const std::vector<double>& du, double residualNorm);
  // Particle i's hourglass energy (stiffness kappa V) into K and the residual of field `field`.
  void addHourglassStiffness(const EquilibriumProblem& problem, const InterpolationWeights& W,
                             long i, const Vec3& xp, double stiffness, int field, bool withTangent);

  std::vector<std::vector<Vec3>> u_;          // per field, by node
  std::vector<std::vector<int>> row_;         // per field, by node: block row, or -1
  std::vector<std::pair<int, int>> unknown_;  // block row -> (field, node)
  BlockMatrix K_;
  std::vector<double> residual_, coordinates_;
  std::vector<int> fixed_;
  // Per material and particle: kappa V of the hourglass stabilization, fixed for the step.
  std::vector<std::vector<double>> hourglassStiffness_;
  TaskTimers* timers_ = nullptr;
  int assemblyTask_ = -1, solveTask_ = -1;
};

}  // namespace anode
