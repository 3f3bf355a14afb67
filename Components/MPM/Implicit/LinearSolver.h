// The linear solves of one Newton solve, by PETSc: GMRES preconditioned by algebraic multigrid
// (GAMG) on the system scaled symmetrically by its diagonal, with the nodes' rigid-body modes
// (scaled alike) as GAMG's near-null space. The matrix keeps one pattern for all the solves, and
// the preconditioner built in the first solve serves the later ones while it keeps the Krylov
// iterations low (docs/quasi-static.md). PETSC_OPTIONS (the environment) may change any of it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/Implicit/BlockMatrix.h"

namespace anode {

struct LinearSolve {
  int iterations = 0;
  bool converged = false;
  std::string reason;              // PETSc's KSPConvergedReason
  bool newPreconditioner = false;  // the preconditioner was built for this solve
};

class LinearSolver {
 public:
  // For systems with the pattern of `pattern`; x_i = 0 and the row and column of i removed for
  // each i of `fixed` (a component 3 r + a of block row r); `coordinates` (3 per block row) give
  // the rigid-body modes.
  LinearSolver(const BlockMatrix& pattern, std::vector<int> fixed, std::vector<double> coordinates);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Solves K x = b, K with the constructor's pattern; `relativeTolerance` bounds the scaled
  // residual relative to the scaled b's norm. The fixed components of x are exactly zero.
  LinearSolve solve(const BlockMatrix& K, const std::vector<double>& b, double relativeTolerance,
                    std::vector<double>& x);

 private:
  struct Objects;
  // Scales K into the PETSc matrix's values (fixed rows and columns: identity) and sets scale_.
  void setMatrix(const BlockMatrix& K);
  // Where the values of scalar row 3 r + a start in the AIJ matrix: each block row's 3 rows hold
  // its blocks' columns in K's order.
  static size_t valueOffset(const BlockMatrix& K, int r, int a);
  // Throws unless the PETSc matrix is laid out as valueOffset says.
  void checkLayout(const BlockMatrix& pattern);
  // GAMG's near-null space: the rigid modes of the scaled system, orthonormal.
  void setNearNullSpace();
  // One KSPSolve with the preconditioner built anew or reused.
  LinearSolve run(const std::vector<double>& b, double relativeTolerance, bool newPreconditioner,
                  std::vector<double>& x);

  std::unique_ptr<Objects> o_;
  std::vector<int> fixed_;
  std::vector<char> isFixed_;  // by component: 1 where fixed
  std::vector<double> coordinates_, scale_;
  int freshIterations_ = -1;  // Krylov iterations of the last solve with a new preconditioner
};

}  // namespace anode
