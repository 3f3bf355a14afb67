// The linear solves of one Newton solve, by PETSc: GMRES preconditioned by algebraic multigrid
// (GAMG) on the system scaled symmetrically by its diagonal, with the nodes' rigid-body modes
// (scaled alike) as GAMG's near-null space. The matrix keeps one pattern for all the solves, and
// the preconditioner built in the first solve serves the later ones while it keeps the Krylov
// iterations low (docs/quasi-static.md). PETSC_OPTIONS (the environment) may change any of it.
// In a distributed run the system is PETSc's over all ranks: each rank owns a range of block
// rows and adds its particles' parts of the rows of other ranks' nodes too.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/Implicit/BlockMatrix.h"
#include "Core/Parallel/Communicator.h"

struct _p_Mat;  // PETSc's Mat is a _p_Mat*

namespace anode {

using PetscValue = double;  // PETSc's scalar (real, double precision)

struct LinearSolve {
  int iterations = 0;
  bool converged = false;
  std::string reason;              // PETSc's KSPConvergedReason
  bool newPreconditioner = false;  // the preconditioner was built for this solve
  // |x| |K x - b| (over all ranks): x.b - x.K x lies within +-energySlack (Cauchy-Schwarz), so
  // x.b < -energySlack shows x.K x < 0, and a smaller negative x.b is the inexact solve's.
  double energySlack = 0;
};

// This rank's block rows of the system: the first `owned` rows of its matrices are the global
// rows firstRow, firstRow + 1, ... of this rank; the others (the nodes it shares with ranks that
// own them) carry its parts of other ranks' rows. globalRow: every local row's global row.
struct RowLayout {
  int owned = 0;
  std::vector<int> globalRow;
};

class LinearSolver {
 public:
  // For systems with the pattern of `pattern` (local rows and
  // columns); x_i = 0 and the row and column of i removed for each i of `fixed` (a component
  // 3 r + a of local block row r, owned or not); `coordinates` (3 per owned block row) give the
  // rigid-body modes.
  LinearSolver(Collective, const BlockMatrix& pattern, RowLayout rows,
               const std::vector<int>& fixed, std::vector<double> coordinates);
  // Frees its PETSc objects, collective on PETSc's side: every rank's owner ends it in the same
  // place.
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Solves K x = b, K (this rank's parts, local rows) with the constructor's pattern,
  // b and x on the owned rows (b may hold more); `relativeTolerance` bounds the scaled residual
  // relative to the scaled b's norm. The fixed components of x are exactly zero. Without
  // `newValues` K is the one of the last solve, whose matrix (and preconditioner) it keeps.
  LinearSolve solve(Collective, const BlockMatrix& K, const std::vector<double>& b,
                    double relativeTolerance, std::vector<double>& x, bool newValues = true);

 private:
  struct Objects;
  // The PETSc matrix (every rank's parts of K added; fixed rows and columns: identity) scaled
  // symmetrically by its diagonal; sets scale_ and nonFinite_.
  void setMatrix(Collective, const BlockMatrix& K);
  // Block row r of K added to `target` (the preallocator, or the matrix for rows of other ranks).
  void addRow(_p_Mat* target, const BlockMatrix& K, int r);
  // Entry (a, g) of block e = (r, c) of K as the PETSc matrix holds it (fixed components: 0, and 1
  // on the owner's diagonal).
  double entryOf(const BlockMatrix& K, int r, int c, int e, int a, int g) const;
  // Sets entryAt_ from the pattern after PETSc laid it out.
  void locateOwnedEntries(Collective, const BlockMatrix& pattern);
  // GAMG's near-null space: the rigid modes of the scaled system, orthonormal.
  void setNearNullSpace(Collective);
  // One KSPSolve with the preconditioner built anew or reused.
  LinearSolve run(Collective, const std::vector<double>& b, double relativeTolerance,
                  bool newPreconditioner, std::vector<double>& x);

  std::unique_ptr<Objects> o_;
  RowLayout rows_;
  std::vector<int> fixedOwned_;              // the fixed components of owned rows
  std::vector<char> isFixed_;                // by local component: 1 where fixed
  std::vector<double> coordinates_, scale_;  // of the owned rows' components
  std::vector<PetscValue> rowValues_;
  std::vector<int> rowColumns_;
  // For block e of an owned row of K and its row a: where its first column lies in PETSc's
  // arrays (>= 0: the own-column part's; else -1 - the place in the other part's).
  std::vector<int> entryAt_;
  // Krylov iterations of the last solve with a new preconditioner (< 0: the next solve builds
  // one) and the decades its residual fell.
  int freshIterations_ = -1;
  bool nonFinite_ = false;  // the matrix holds an entry that is not a number (on some rank)
  double freshDecades_ = 1;
};

}  // namespace anode
