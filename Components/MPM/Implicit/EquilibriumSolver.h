// Newton's method for the equilibrium of one quasi-static step on the grid (DESIGN.md §4b, step
// 3; docs/quasi-static.md): the unknowns are the displacement increments of the nodes the
// particles reach, one set per velocity field (materials in single_velocity contact share one,
// with null contact each body has its own); the residual is the external force (gravity) minus
// the internal force of the trial stresses (and, in implicit dynamics, minus m a: Newmark.h); the
// Jacobian is assembled from the particles' algorithmic tangents; Symmetric and Velocity faces fix
// components. ImpMPM's convergence test.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/GhostNodes.h"
#include "Components/MPM/Implicit/BlockMatrix.h"
#include "Components/MPM/Implicit/LinearSolver.h"
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
  // A distributed run: the nodes shared with other ranks (null on one rank), this step's reach
  // covering every shared node this rank owns, and by node 1 where this rank owns the node's
  // unknowns (empty: every node).
  GhostNodes* ghosts = nullptr;
  std::vector<char> owned;
  // Implicit dynamics (<dynamic>true; Implicit/Newmark.h): per field and node, the velocity and
  // acceleration of the step's start. Empty in a quasi-static step.
  std::vector<std::vector<Vec3>> velocity, acceleration;
  // A quasi-static step: per field and node, the increment the start-of-step nodal velocity would
  // give (v dt), Newton's first iterate where it lowers the residual. Empty: none. Solved: it is
  // a converged Newton solve's (the trapezoidal step's prediction), not an extrapolation.
  std::vector<std::vector<Vec3>> predicted;
  bool predictedIsSolved = false;
  // The trapezoidal step's prediction and its main solve, both from the step's start (the same
  // particles and weights): the prediction keeps its unknowns and linear solver (PETSc's matrix
  // layout and GAMG's preconditioner) for the main solve, which takes them when its nodal masses
  // and prescribed components are the prediction's on every rank. Otherwise each solve numbers
  // its own unknowns, builds its own solver and frees it at its end.
  bool keepLinearSolver = false, useKeptLinearSolver = false;
};

// How Newton went in one attempt at a step.
struct NewtonReport {
  bool converged = false;
  int iterations = 0, krylovIterations = 0;
  int newTangents = 0;  // iterations that assembled the Jacobian (the others kept the last one)
  int preconditionerSetUps = 0;  // GAMG built for a matrix (docs/quasi-static.md, linear solves)
  // Per iteration: |du|^2 / max, du.r / first (ImpMPM's two ratios).
  std::vector<std::pair<double, double>> ratios;
  std::vector<double> linearTolerances;  // per iteration: its linear solve's relative tolerance
  std::string failure;                   // why it did not converge
};

// In a distributed run every rank solves together (the functions are collective): each owns the
// unknowns of the nodes in its box (Decomposition::ownerOfCell of the node's index), sums its
// particles' parts into the rows of every node they reach, and the ranks complete the residual
// and share the corrections on the nodes they share (GhostNodes).
class EquilibriumSolver {
 public:
  // Task timers: assembly (trial stresses, tangents, forces), linear solve.
  void useTimers(TaskTimers& timers);
  // Newton for the step of length dt; on success displacement(f) holds the converged nodal
  // increments of field f (by node).
  NewtonReport solve(Collective, const EquilibriumProblem& problem, double dt,
                     const ImplicitOptions& options);
  const std::vector<Vec3>& displacement(int field) const { return u_[field]; }
  // Implicit dynamics: the nodal accelerations at the end of the converged step (Newmark's;
  // zero on the nodes left out of the unknowns).
  const std::vector<Vec3>& acceleration(int field) const { return acceleration_[field]; }
  // For verification (tests/test_tangent.cc), on one rank: the residual r at the nodal increments
  // u (per field, by node; the prescribed components as given) and Newton's Jacobian there (the
  // stiffness K, -dr/du) times du, both per field by node (zero off the unknowns and on the fixed
  // components), with the hourglass stiffness of the step's start as a solve fixes it. Defined in
  // EquilibriumAssembly.cc.
  struct Linearization {
    std::vector<std::vector<Vec3>> residual, jacobianTimesDirection;
  };
  Linearization linearizeAt(Collective, const EquilibriumProblem& problem, double dt,
                            const ImplicitOptions& options, const std::vector<std::vector<Vec3>>& u,
                            const std::vector<std::vector<Vec3>>& du);

 private:
  // EquilibriumNumbering.cc: the unknowns, their layout over the ranks and the linear solver.
  // The unknown nodes (block rows: this rank's own first, then the ones it shares with their
  // owners), their global rows, the pattern of their couplings (couplings_, in a reduced
  // Jacobian) and of the Jacobian (K_), from the weights: a particle couples a pair of nodes in K_
  // only where it holds at least `jacobianCouplingShare` of both nodes' mass (ImplicitOptions).
  void numberUnknowns(Collective, const EquilibriumProblem& problem, double jacobianCouplingShare);
  // values (`width` per block row): on a distributed run, every rank's parts summed on the shared
  // rows; with `fromOwners`, the owned rows' values copied to the other ranks' rows of the same
  // nodes (the others' parts set to zero first).
  void completeOverRanks(Collective, const EquilibriumProblem& problem, std::vector<double>& values,
                         int width, bool fromOwners) const;
  // sum of a_i b_i over the owned rows' components, over all ranks.
  double ownedDot(Collective, const std::vector<double>& a, const std::vector<double>& b) const;
  // The problem asks for the kept linear solver and on every rank its nodal masses
  // and prescribed components are those the unknowns were numbered for. The particles and their
  // weights are the same by the problem's contract (EquilibriumProblem::useKeptLinearSolver), so
  // the unknowns, K's pattern and the linear solver all stand.
  bool takesKeptLinearSolver(Collective, const EquilibriumProblem& problem) const;
  // A new linearSolver_ for this solve's unknowns (the old one freed first).
  void buildLinearSolver(Collective, const EquilibriumProblem& problem);

  // EquilibriumAssembly.cc: the residual and Jacobian at the current u.
  // K and the residual r = f_ext - f_int (- m a) at the current u (fixed components of r zeroed).
  // `stabilization`: epsilon of Implicit/HourglassStabilization.h. Without the tangent: the
  // residual only (the line search's trials).
  void assemble(Collective, const EquilibriumProblem& problem, double dt, double stabilization,
                bool withTangent);
  // Material m's particles' internal forces (and their stiffness) into the block rows [first,
  // last) of the residual (and K).
  void addInternalForce(const EquilibriumProblem& problem, size_t m, int first, int last,
                        bool withTangent);
  // Material m's hourglass energies (Implicit/HourglassStabilization.h) into the rows [first,
  // last) of hourglass_ and hourglassLoad_.
  void addHourglassStiffness(const EquilibriumProblem& problem, size_t m, double stabilization,
                             int first, int last);
  // The hourglass forces -(hourglass_ u + hourglassLoad_) into the rows [first, last) of the
  // residual (and hourglass_ I into K).
  void applyHourglassStiffness(int first, int last, bool withTangent);

  // EquilibriumRigidModes.cc: the rigid modes of the free bodies.
  // A quasi-static body faces hold only in part (or not at all) has rigid modes no equation sets:
  // of each field, the part of the correction du (by block row) that moves it rigidly in a way
  // its fixed components allow (translations and rotations vanishing on all of them) is removed,
  // by mass, so an inexact solve does not move the body. K's regularization alpha m I keeps
  // those modes solvable, not the residual.
  void removeRigidMotionOfFreeBodies(Collective, const EquilibriumProblem& problem,
                                     std::vector<double>& du) const;

  // EquilibriumSolver.cc: the Newton loop.
  // u_ at the step's start: the prescribed components, zero elsewhere.
  void startFromPrescribed(const EquilibriumProblem& problem);
  // u += scale du (du by block row).
  void addToDisplacement(const std::vector<double>& du, double scale);
  // Newton's update u += s du with the line search's fraction s (EquilibriumSolver.cc);
  // `residualNorm` is |r|^2 at u, `energy` du.r there. Whether residual_ is that of the new u.
  bool takeStep(Collective, const EquilibriumProblem& problem, double dt, double stabilization,
                const std::vector<double>& du, double residualNorm, double energy);
  // After the first assembly (at the start-of-step u): u moves to the predicted increments of
  // the unknowns when their residual is lower (the first solve then uses the tangent of the
  // start, or the one kept from the prediction's solve), and the references of the convergence
  // ratios become those of the step's size, as a Newton from the start would have them:
  // |predicted|^2 and predicted.r at the start. Whether it moved.
  bool tryPrediction(Collective, const EquilibriumProblem& problem, double dt, double stabilization,
                     double& normReference, double& energyReference);
  // The end-of-step accelerations of implicit dynamics (Newmark) into acceleration_.
  void computeEndOfStepAcceleration(const EquilibriumProblem& problem, double dt);

  std::vector<std::vector<Vec3>> u_;             // per field, by node
  std::vector<std::vector<Vec3>> acceleration_;  // per field, by node (implicit dynamics)
  std::vector<std::vector<int>> row_;            // per field, by node: block row, or -1
  std::vector<std::pair<int, int>> unknown_;     // block row -> (field, node)
  RowLayout rows_;                               // which rows this rank owns; global rows
  BlockMatrix K_;
  // A Jacobian reduced by <jacobian_coupling_share>: then every pair of unknown nodes one particle
  // reaches (the residual's couplings; no blocks) is in couplings_; otherwise they are K_'s
  // pattern. And per block row the place of its diagonal block in K_.
  bool reduced_ = false;
  BlockMatrix couplings_;
  const BlockMatrix& residualPattern() const { return reduced_ ? couplings_ : K_; }
  std::vector<int> diagonal_;
  // Per material and weight entry: 1 where the particle couples the entry's node in K_.
  std::vector<std::vector<char>> strong_;
  // Per material: its particles in the order the assembly adds them (by first node).
  std::vector<std::vector<size_t>> order_;
  std::vector<double> residual_, coordinates_;  // coordinates: of the owned rows
  std::vector<int> fixed_;                      // fixed components of the rows
  // Per material and particle: the trial stress P and its tangent dP/dH.
  std::vector<std::vector<Mat3>> P_;
  std::vector<std::vector<Mat9>> A_;
  // The hourglass stiffness, fixed for the step: a scalar per block entry of residualPattern()
  // (times the 3 x 3 identity), its part in a reduced Jacobian per block entry of K_ (the
  // particles' couplings as for their own stiffness; otherwise hourglass_ is that part), and the
  // constant force of the nodes left out of the unknowns (3 per block row).
  std::vector<double> hourglass_, hourglassTangent_, hourglassLoad_;
  std::unique_ptr<LinearSolver> linearSolver_;
  // What a converged solve that keeps its linear solver leaves the next solve from the same
  // start: K's values of its last iteration (the tangent near its solution) and the step's
  // hourglass stiffness. Taken (or freed) by the next solve.
  struct KeptTangent {
    std::vector<Mat3> block;
    std::vector<double> hourglass, hourglassTangent, hourglassLoad;
  } kept_;
  // The nodal masses and prescribed components the unknowns of a kept linear solver were
  // numbered for (empty when it is not kept).
  std::vector<std::vector<double>> numberedMass_;
  std::vector<std::vector<Vec3>> numberedPrescribed_;
  TaskTimers* timers_ = nullptr;
  int assemblyTask_ = -1, solveTask_ = -1;
};

}  // namespace anode
