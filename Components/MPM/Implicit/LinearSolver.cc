#include "Components/MPM/Implicit/LinearSolver.h"

#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"
#include "Core/Util/StepActivity.h"

namespace anode {

namespace {

// A solve with the preconditioner of an earlier matrix stops after this many Krylov iterations;
// then the preconditioner is built for the current matrix and the system solved again.
constexpr int kReusedPreconditionerIterations = 100;
// The preconditioner is also built anew for the next solve when the last one needed more than
// this many times the iterations of the last solve with a new preconditioner (at least 5), those
// scaled by the decades the residual had to fall when the last one's tolerance was tighter:
// Newton's solves have tolerances from 0.1 to 1e-9.
constexpr int kReusedPreconditionerSlowdown = 4;
// A solve with a new preconditioner fails after this many: the ones that converge take at most
// a few hundred (Figure 4's pillar: 197 in all 9 solves of its first step), and a failing one costs
// Newton a retake at a smaller dt anyway.
constexpr int kMaxIterations = 500;

// A PETSc call that failed, in PETSc's words: a LibraryFailure (exit 3; Errors.h).
void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  std::string message =
      std::string("PETSc's ") + what + " failed (error " + std::to_string(static_cast<int>(code));
  if (text) message += std::string(": ") + text;
  if (specific && *specific) message += std::string(": ") + specific;
  throw LibraryFailure(message + ")");
}

void endPetsc() {
  PetscFinalize();
}

// PETSc starts with the first solve and ends before MPI does.
void startPetsc(Collective) {
  PetscBool started = PETSC_FALSE;
  check(PetscInitialized(&started), "PetscInitialized");
  if (started) return;
  check(PetscInitializeNoArguments(), "PetscInitialize");
  // PETSc's errors come back as codes, and check() reports them: PETSc prints nothing itself.
  check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
  Communicator::beforeStop(endPetsc);
}

// KSP's default convergence test, and a stop request (StopRequest.h) of any rank ends the solve
// between two Krylov iterations: `stopped`, for LinearSolver::run to throw StopRequestedInStep
// (not through PETSc). Every rank tests the same iteration: one reduction of a bool each.
struct StopTest {
  Collective every;
  void* defaults = nullptr;  // KSPConvergedDefault's context
  bool stopped = false;
};

PetscErrorCode convergedOrStopped(KSP ksp, PetscInt iteration, PetscReal norm,
                                  KSPConvergedReason* reason, void* context) {
  auto* test = static_cast<StopTest*>(context);
  PetscCall(KSPConvergedDefault(ksp, iteration, norm, reason, test->defaults));
  noteStepActivity(1, "Krylov iteration", iteration);
  if (*reason == KSP_CONVERGED_ITERATING && collective::any(test->every, stopRequested())) {
    test->stopped = true;
    *reason = KSP_DIVERGED_ITS;
  }
  return 0;
}

PetscErrorCode destroyStopTest(void* context) {
  auto* test = static_cast<StopTest*>(context);
  PetscCall(KSPConvergedDefaultDestroy(test->defaults));
  delete test;
  return 0;
}

}  // namespace

// One PETSc object of each kind the solves use.
struct LinearSolver::Objects {
  Mat A = nullptr;
  // The sequential matrices of this rank's rows of A (A itself on one rank): A's, not destroyed.
  Mat part[2] = {nullptr, nullptr};
  Vec x = nullptr, b = nullptr, scale = nullptr, residual = nullptr;
  KSP ksp = nullptr;
  StopTest* stopTest = nullptr;  // the ksp's (destroyed with it)
  ~Objects() {
    KSPDestroy(&ksp);
    VecDestroy(&residual);
    VecDestroy(&scale);
    VecDestroy(&b);
    VecDestroy(&x);
    MatDestroy(&A);
  }
};

LinearSolver::LinearSolver(Collective every, const BlockMatrix& pattern, RowLayout rows,
                           const std::vector<int>& fixed, std::vector<double> coordinates)
    : o_(std::make_unique<Objects>()),
      rows_(std::move(rows)),
      coordinates_(std::move(coordinates)) {
  static_assert(sizeof(PetscInt) == sizeof(int), "PETSc with 32-bit indices");
  static_assert(sizeof(PetscScalar) == sizeof(PetscValue), "PETSc with real double scalars");
  startPetsc(every);
  const PetscInt n = 3 * rows_.owned;
  isFixed_.assign(3 * static_cast<size_t>(pattern.rows()), 0);
  for (int i : fixed) {
    isFixed_[i] = 1;
    if (i < n) fixedOwned_.push_back(i);
  }
  // The pattern: every 3 x 3 block of every rank's K, zeros included, counted by PETSc's
  // preallocator (rows of other ranks included), then laid out in the matrix.
  Mat counter = nullptr;
  check(MatCreate(PETSC_COMM_WORLD, &counter), "MatCreate");
  check(MatSetType(counter, MATPREALLOCATOR), "MatSetType");
  check(MatSetSizes(counter, n, n, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetBlockSize(counter, 3), "MatSetBlockSize");
  check(MatSetUp(counter), "MatSetUp");
  for (int r = 0; r < pattern.rows(); ++r) addRow(counter, pattern, r);
  check(MatAssemblyBegin(counter, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(counter, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  check(MatCreate(PETSC_COMM_WORLD, &o_->A), "MatCreate");
  check(MatSetSizes(o_->A, n, n, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(o_->A, MATAIJ), "MatSetType");
  check(MatSetBlockSize(o_->A, 3), "MatSetBlockSize");
  check(MatPreallocatorPreallocate(counter, PETSC_TRUE, o_->A), "MatPreallocatorPreallocate");
  MatDestroy(&counter);
  // Every later assembly sends the same rows to the same ranks.
  check(MatSetOption(o_->A, MAT_SUBSET_OFF_PROC_ENTRIES, PETSC_TRUE), "MatSetOption");
  // An entry outside the pattern would move the places entryAt_ holds: an error instead.
  check(MatSetOption(o_->A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  locateOwnedEntries(every, pattern);
  check(MatCreateVecs(o_->A, &o_->x, &o_->b), "MatCreateVecs");
  check(VecDuplicate(o_->b, &o_->scale), "VecDuplicate");
  check(VecDuplicate(o_->b, &o_->residual), "VecDuplicate");
  check(KSPCreate(PETSC_COMM_WORLD, &o_->ksp), "KSPCreate");
  check(KSPSetType(o_->ksp, KSPGMRES), "KSPSetType");
  check(KSPGMRESSetRestart(o_->ksp, 200), "KSPGMRESSetRestart");
  // Right preconditioning: GMRES minimizes the residual of the system itself, which is what the
  // tolerance of an inexact Newton step bounds (left preconditioning bounds the preconditioned
  // residual, whose relation to it changes as the preconditioner ages).
  check(KSPSetPCSide(o_->ksp, PC_RIGHT), "KSPSetPCSide");
  PC pc = nullptr;
  check(KSPGetPC(o_->ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  // Each new preconditioner is built for its own matrix. By default a set-up for a new matrix of
  // the same pattern keeps GAMG's prolongator (PETSc 3.18) and, with it, the eigenvalue estimate
  // of an earlier matrix made while smoothing it, which GAMG hands to its Chebyshev smoothers: once
  // the pillar yields they amplify what they should damp (the large pillar's first step: 2,116
  // Krylov iterations in 16 Newton iterations; 119 in 9 with the preconditioner built anew).
  check(PCGAMGSetReuseInterpolation(pc, PETSC_FALSE), "PCGAMGSetReuseInterpolation");
  check(KSPSetFromOptions(o_->ksp), "KSPSetFromOptions");
  o_->stopTest = new StopTest{every};
  check(KSPConvergedDefaultCreate(&o_->stopTest->defaults), "KSPConvergedDefaultCreate");
  check(KSPSetConvergenceTest(o_->ksp, convergedOrStopped, o_->stopTest, destroyStopTest),
        "KSPSetConvergenceTest");
}

LinearSolver::~LinearSolver() = default;

double LinearSolver::entryOf(const BlockMatrix& K, int r, int c, int e, int a, int g) const {
  const int row = 3 * r + a, column = 3 * c + g;
  if (isFixed_[row] || isFixed_[column])  // the owner's 1 on the diagonal
    return r < rows_.owned && row == column ? 1.0 : 0.0;
  return K.block[e](a, g);
}

void LinearSolver::addRow(Mat target, const BlockMatrix& K, int r) {
  const int begin = K.rowStart[r], count = K.rowStart[r + 1] - begin;
  if (count == 0) return;
  // Row-major, as PETSc reads a block row: scalar row a holds (a, 3 j + g) for block j.
  rowValues_.resize(9 * static_cast<size_t>(count));
  rowColumns_.resize(count);
  for (int j = 0; j < count; ++j) {
    const int c = K.column[begin + j];
    rowColumns_[j] = rows_.globalRow[c];
    for (int a = 0; a < 3; ++a)
      for (int g = 0; g < 3; ++g)
        rowValues_[3 * count * a + 3 * j + g] = entryOf(K, r, c, begin + j, a, g);
  }
  const PetscInt row = rows_.globalRow[r];
  check(MatSetValuesBlocked(target, 1, &row, count, rowColumns_.data(), rowValues_.data(),
                            ADD_VALUES),
        "MatSetValuesBlocked");
}

void LinearSolver::locateOwnedEntries(Collective, const BlockMatrix& pattern) {
  // This rank's rows of A: one sequential matrix, or (several ranks) the columns of its own rows
  // (part 0, local columns) and the others (part 1, columns by the sorted `global` list).
  const PetscInt* global = nullptr;
  PetscBool sequential = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(o_->A), MATSEQAIJ, &sequential),
        "PetscObjectTypeCompare");
  if (sequential)
    o_->part[0] = o_->A;
  else
    check(MatMPIAIJGetSeqAIJ(o_->A, &o_->part[0], &o_->part[1], &global), "MatMPIAIJGetSeqAIJ");
  PetscInt firstRow = 0, endRow = 0, globalColumns = 0;
  check(MatGetOwnershipRange(o_->A, &firstRow, &endRow), "MatGetOwnershipRange");
  if (o_->part[1]) check(MatGetSize(o_->part[1], nullptr, &globalColumns), "MatGetSize");
  const PetscInt* rowStart[2] = {nullptr, nullptr};
  const PetscInt* column[2] = {nullptr, nullptr};
  // PETSc's compressed rows of each part (get), handed back when done (restore).
  const auto rowsOfParts = [&](bool get) {
    for (int part = 0; part < 2; ++part) {
      if (!o_->part[part]) continue;
      PetscInt rows = 0;
      PetscBool done = PETSC_FALSE;
      const auto call = get ? MatGetRowIJ : MatRestoreRowIJ;
      const char* name = get ? "MatGetRowIJ" : "MatRestoreRowIJ";
      check(call(o_->part[part], 0, PETSC_FALSE, PETSC_FALSE, &rows, &rowStart[part], &column[part],
                 &done),
            name);
      if (!done) throw std::runtime_error(std::string("PETSc: ") + name + " did nothing");
    }
  };
  rowsOfParts(true);
  // Each block's three columns are adjacent in every scalar row: the first one's place is kept,
  // for part 1 as -1 - place.
  entryAt_.assign(3 * pattern.column.size(), 0);
  for (int r = 0; r < rows_.owned; ++r)
    for (int e = pattern.rowStart[r]; e < pattern.rowStart[r + 1]; ++e) {
      const PetscInt first = 3 * static_cast<PetscInt>(rows_.globalRow[pattern.column[e]]);
      const bool own = first >= firstRow && first < endRow;
      const int part = own ? 0 : 1;
      const PetscInt wanted =
          own ? first - firstRow
              : static_cast<PetscInt>(std::lower_bound(global, global + globalColumns, first) -
                                      global);
      for (int a = 0; a < 3; ++a) {
        const PetscInt row = 3 * r + a;
        const PetscInt* begin = column[part] + rowStart[part][row];
        const PetscInt* end = column[part] + rowStart[part][row + 1];
        const PetscInt* at = std::lower_bound(begin, end, wanted);
        if (at == end || *at != wanted)
          throw std::logic_error("a block of K outside PETSc's pattern");
        const int place = static_cast<int>(at - column[part]);
        entryAt_[3 * static_cast<size_t>(e) + a] = own ? place : -1 - place;
      }
    }
  rowsOfParts(false);
}

void LinearSolver::setMatrix(Collective every, const BlockMatrix& K) {
  // The owned rows' entries written where they lie in PETSc's arrays, the other rows added
  // through PETSc (to the ranks that own them) when the matrix is assembled.
  check(MatZeroEntries(o_->A), "MatZeroEntries");
  PetscScalar* values[2] = {nullptr, nullptr};
  for (int part = 0; part < 2; ++part)
    if (o_->part[part])
      check(MatSeqAIJGetArray(o_->part[part], &values[part]), "MatSeqAIJGetArray");
  bool finite = true;
  for (int r = 0; r < rows_.owned; ++r)
    for (int e = K.rowStart[r]; e < K.rowStart[r + 1]; ++e) {
      const int c = K.column[e];
      for (int a = 0; a < 3; ++a) {
        const int at = entryAt_[3 * static_cast<size_t>(e) + a];
        PetscScalar* v = at >= 0 ? values[0] + at : values[1] + (-at - 1);
        for (int g = 0; g < 3; ++g) {
          v[g] = entryOf(K, r, c, e, a, g);
          finite &= std::isfinite(v[g]);
        }
      }
    }
  for (int part = 0; part < 2; ++part)
    if (o_->part[part])
      check(MatSeqAIJRestoreArray(o_->part[part], &values[part]), "MatSeqAIJRestoreArray");
  for (int r = rows_.owned; r < K.rows(); ++r) {
    for (int e = K.rowStart[r]; e < K.rowStart[r + 1]; ++e) finite &= K.block[e].allFinite();
    addRow(o_->A, K, r);
  }
  // Every rank knows before any of them calls PETSc with it (solve gives up on such a matrix).
  nonFinite_ = collective::any(every, !finite);
  check(MatAssemblyBegin(o_->A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(o_->A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  // Symmetric diagonal scaling, D K D with D = |diag K|^-1/2: nodes a particle's corner just
  // reaches have stiffness 1e-8 of the others', which breaks GMRES down on the unscaled system.
  check(MatGetDiagonal(o_->A, o_->scale), "MatGetDiagonal");
  PetscScalar* d = nullptr;
  check(VecGetArray(o_->scale, &d), "VecGetArray");
  scale_.resize(3 * static_cast<size_t>(rows_.owned));
  for (size_t i = 0; i < scale_.size(); ++i) {
    scale_[i] = d[i] != 0 ? 1 / std::sqrt(std::abs(d[i])) : 1.0;
    d[i] = scale_[i];
  }
  check(VecRestoreArray(o_->scale, &d), "VecRestoreArray");
  check(MatDiagonalScale(o_->A, o_->scale, o_->scale), "MatDiagonalScale");
}

void LinearSolver::setNearNullSpace(Collective every) {
  const size_t n = scale_.size(), blocks = n / 3;
  // The centre of every rank's nodes.
  double sums[4] = {0, 0, 0, static_cast<double>(blocks)};
  for (size_t r = 0; r < blocks; ++r)
    for (int a = 0; a < 3; ++a) sums[a] += coordinates_[3 * r + a];
  collective::sum(every, sums, 4);
  Vec3 centre(sums[0], sums[1], sums[2]);
  if (sums[3] > 0) centre /= sums[3];
  // Rigid modes m of K are modes D^-1 m of D K D; fixed components are decoupled rows.
  std::vector<std::vector<double>> modes;
  for (int k = 0; k < 6; ++k) {
    std::vector<double> m(n);
    for (size_t r = 0; r < blocks; ++r) {
      const Vec3 x =
          Vec3(coordinates_[3 * r], coordinates_[3 * r + 1], coordinates_[3 * r + 2]) - centre;
      Vec3 v = Vec3::Zero();
      if (k < 3)
        v[k] = 1;
      else
        v = Vec3::Unit(k - 3).cross(x);
      for (int a = 0; a < 3; ++a) m[3 * r + a] = v[a] / scale_[3 * r + a];
    }
    for (int i : fixedOwned_) m[i] = 0;
    const auto dot = [n, every](const std::vector<double>& a, const std::vector<double>& b) {
      double d = 0;
      for (size_t i = 0; i < n; ++i) d += a[i] * b[i];
      return collective::sum(every, d);
    };
    const double before = dot(m, m);
    // Modified Gram-Schmidt; a mode the fixed components remove is dropped.
    for (const std::vector<double>& q : modes) {
      const double projection = dot(q, m);
      for (size_t i = 0; i < n; ++i) m[i] -= projection * q[i];
    }
    const double norm = dot(m, m);
    if (!(norm > 1e-20 * before)) continue;
    for (double& v : m) v /= std::sqrt(norm);
    modes.push_back(std::move(m));
  }
  std::vector<Vec> vectors(modes.size(), nullptr);
  for (size_t k = 0; k < modes.size(); ++k) {
    check(VecDuplicate(o_->b, &vectors[k]), "VecDuplicate");
    double* v = nullptr;
    check(VecGetArray(vectors[k], &v), "VecGetArray");
    std::copy(modes[k].begin(), modes[k].end(), v);
    check(VecRestoreArray(vectors[k], &v), "VecRestoreArray");
  }
  MatNullSpace space = nullptr;
  check(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(vectors.size()),
                           vectors.data(), &space),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(o_->A, space), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&space);
  for (Vec& v : vectors) VecDestroy(&v);
}

LinearSolve LinearSolver::run(Collective every, const std::vector<double>& b,
                              double relativeTolerance, bool newPreconditioner,
                              std::vector<double>& x) {
  if (newPreconditioner) setNearNullSpace(every);
  check(KSPSetReusePreconditioner(o_->ksp, newPreconditioner ? PETSC_FALSE : PETSC_TRUE),
        "KSPSetReusePreconditioner");
  check(KSPSetOperators(o_->ksp, o_->A, o_->A), "KSPSetOperators");
  check(KSPSetTolerances(o_->ksp, relativeTolerance, 0.0, PETSC_DEFAULT,
                         newPreconditioner ? kMaxIterations : kReusedPreconditionerIterations),
        "KSPSetTolerances");
  double* bb = nullptr;
  check(VecGetArray(o_->b, &bb), "VecGetArray");
  for (size_t i = 0; i < scale_.size(); ++i) bb[i] = scale_[i] * b[i];
  for (int i : fixedOwned_) bb[i] = 0;
  check(VecRestoreArray(o_->b, &bb), "VecRestoreArray");
  check(KSPSolve(o_->ksp, o_->b, o_->x), "KSPSolve");
  if (o_->stopTest->stopped) throw StopRequestedInStep();

  LinearSolve s;
  s.newPreconditioner = newPreconditioner;
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(o_->ksp, &iterations), "KSPGetIterationNumber");
  s.iterations = static_cast<int>(iterations);
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(o_->ksp, &reason), "KSPGetConvergedReason");
  s.converged = reason > 0;
  s.reason = KSPConvergedReasons[reason];
  // In the scaled system (x = D y, b = D^-1 c): x.b = y.c and x.K x = y.(D K D) y.
  PetscReal residualNorm = 0, solutionNorm = 0;
  check(MatMult(o_->A, o_->x, o_->residual), "MatMult");
  check(VecAYPX(o_->residual, -1.0, o_->b), "VecAYPX");
  check(VecNorm(o_->residual, NORM_2, &residualNorm), "VecNorm");
  check(VecNorm(o_->x, NORM_2, &solutionNorm), "VecNorm");
  s.energySlack = residualNorm * solutionNorm;
  const double* xs = nullptr;
  check(VecGetArrayRead(o_->x, &xs), "VecGetArrayRead");
  x.resize(scale_.size());
  for (size_t i = 0; i < scale_.size(); ++i) x[i] = scale_[i] * xs[i];
  check(VecRestoreArrayRead(o_->x, &xs), "VecRestoreArrayRead");
  // The fixed components' rows are decoupled, but an inexact solve leaves round-off of its
  // tolerance on them.
  for (int i : fixedOwned_) x[i] = 0;
  return s;
}

namespace {

// The decades a residual falls to reach `relativeTolerance` (at least one).
double decadesOf(double relativeTolerance) {
  return std::max(1.0, -std::log10(relativeTolerance));
}

}  // namespace

LinearSolve LinearSolver::solve(Collective every, const BlockMatrix& K,
                                const std::vector<double>& b, double relativeTolerance,
                                std::vector<double>& x, bool newValues) {
  if (newValues) setMatrix(every, K);
  // A trial state no model can take (an inverted particle) gives entries that are not numbers:
  // a solve that failed, without PETSc, so Newton retakes the step with a smaller dt.
  if (nonFinite_) {
    LinearSolve failed;
    failed.reason = "a Jacobian entry that is not a number";
    return failed;
  }
  LinearSolve s = run(every, b, relativeTolerance, freshIterations_ < 0, x);
  if (!s.newPreconditioner && !s.converged) {  // solved again with a new one
    const int spent = s.iterations;
    s = run(every, b, relativeTolerance, true, x);
    s.iterations += spent;
    freshIterations_ = s.iterations - spent;
    freshDecades_ = decadesOf(relativeTolerance);
  } else if (s.newPreconditioner) {
    freshIterations_ = s.iterations;
    freshDecades_ = decadesOf(relativeTolerance);
  } else if (s.iterations > kReusedPreconditionerSlowdown * std::max(freshIterations_, 5) *
                                std::max(1.0, decadesOf(relativeTolerance) / freshDecades_)) {
    freshIterations_ = -1;
  }
  return s;
}

}  // namespace anode
