// The linear solve of each Newton iteration, by PETSc: GMRES preconditioned by algebraic multigrid
// (GAMG) with the rigid-body modes of the nodes as its near-null space, on the system scaled
// symmetrically by its diagonal; PETSC_OPTIONS (the environment) may change any of it
// (docs/quasi-static.md).
#pragma once

#include <string>
#include <vector>

#include "Components/MPM/Implicit/BlockMatrix.h"

namespace anode {

struct LinearSolve {
  int iterations = 0;
  bool converged = false;
  std::string reason;  // PETSc's KSPConvergedReason
};

// Solves K x = b, with x_i = 0 and the row and column of i removed for each i of `fixed` (a
// component 3 r + a of block row r); `coordinates` (3 per block row) give the near-null space.
// `relativeTolerance` bounds the residual relative to b's norm.
LinearSolve solveLinearSystem(const BlockMatrix& K, const std::vector<double>& b,
                              const std::vector<int>& fixed, const std::vector<double>& coordinates,
                              double relativeTolerance, std::vector<double>& x);

}  // namespace anode
