#include "Components/MPM/Implicit/LinearSolver.h"

#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Core/Parallel/Communicator.h"

namespace anode {

namespace {

// A solve with the preconditioner of an earlier matrix stops after this many Krylov iterations;
// then the preconditioner is built for the current matrix and the system solved again.
constexpr int kReusedPreconditionerIterations = 100;
// The preconditioner is also built anew for the next solve when the last one needed more than
// this many times the iterations of the last solve with a new preconditioner.
constexpr int kReusedPreconditionerSlowdown = 4;
// A solve with a new preconditioner fails after this many: the ones that converge take at most
// a few hundred (Figure 4's pillar: 197 in all 9 solves of its first step), and a failing one costs
// Newton a retake at a smaller dt anyway.
constexpr int kMaxIterations = 500;

void check(PetscErrorCode code, const char* what) {
  if (code != 0)
    throw std::runtime_error(std::string("PETSc: ") + what + " failed (error " +
                             std::to_string(static_cast<int>(code)) + ")");
}

void endPetsc() {
  PetscFinalize();
}

// PETSc starts with the first solve and ends before MPI does.
void startPetsc() {
  PetscBool started = PETSC_FALSE;
  check(PetscInitialized(&started), "PetscInitialized");
  if (started) return;
  check(PetscInitializeNoArguments(), "PetscInitialize");
  Communicator::beforeStop(endPetsc);
}

}  // namespace

// One PETSc object of each kind the solves use.
struct LinearSolver::Objects {
  Mat A = nullptr;
  Vec x = nullptr, b = nullptr, scale = nullptr, residual = nullptr;
  KSP ksp = nullptr;
  ~Objects() {
    KSPDestroy(&ksp);
    VecDestroy(&residual);
    VecDestroy(&scale);
    VecDestroy(&b);
    VecDestroy(&x);
    MatDestroy(&A);
  }
};

LinearSolver::LinearSolver(const BlockMatrix& pattern, RowLayout rows,
                           const std::vector<int>& fixed, std::vector<double> coordinates)
    : o_(std::make_unique<Objects>()),
      rows_(std::move(rows)),
      coordinates_(std::move(coordinates)) {
  static_assert(sizeof(PetscInt) == sizeof(int), "PETSc with 32-bit indices");
  static_assert(sizeof(PetscScalar) == sizeof(PetscValue), "PETSc with real double scalars");
  startPetsc();
  const PetscInt n = 3 * rows_.owned;
  isFixed_.assign(3 * static_cast<size_t>(pattern.rows()), 0);
  for (int i : fixed) {
    isFixed_[i] = 1;
    if (i < n) fixedOwned_.push_back(i);
  }
  // The pattern in PETSc's coordinate form: every entry of every 3 x 3 block of every rank's K
  // (rows of other ranks included), in the order of K's blocks and of a Mat3's storage (column by
  // column), so that setMatrix hands PETSc the values in that order.
  std::vector<PetscInt> rowOf, columnOf;
  rowOf.reserve(9 * pattern.column.size());
  columnOf.reserve(9 * pattern.column.size());
  for (int r = 0; r < pattern.rows(); ++r)
    for (int e = pattern.rowStart[r]; e < pattern.rowStart[r + 1]; ++e)
      for (int g = 0; g < 3; ++g)
        for (int a = 0; a < 3; ++a) {
          rowOf.push_back(3 * rows_.globalRow[r] + a);
          columnOf.push_back(3 * rows_.globalRow[pattern.column[e]] + g);
        }
  check(MatCreate(PETSC_COMM_WORLD, &o_->A), "MatCreate");
  check(MatSetSizes(o_->A, n, n, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(o_->A, MATAIJ), "MatSetType");
  check(MatSetBlockSize(o_->A, 3), "MatSetBlockSize");
  check(MatSetPreallocationCOO(o_->A, static_cast<PetscCount>(rowOf.size()), rowOf.data(),
                               columnOf.data()),
        "MatSetPreallocationCOO");
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
  check(KSPSetFromOptions(o_->ksp), "KSPSetFromOptions");
}

LinearSolver::~LinearSolver() = default;

void LinearSolver::setMatrix(const BlockMatrix& K) {
  // K's values in the constructor's order; a fixed component's row and column are zero but for
  // the owner's 1 on the diagonal. PETSc adds the ranks' parts of each entry.
  values_.resize(9 * K.column.size());
  for (int r = 0; r < K.rows(); ++r) {
    const bool owned = r < rows_.owned;
    for (int e = K.rowStart[r]; e < K.rowStart[r + 1]; ++e) {
      const int c = K.column[e];
      for (int g = 0; g < 3; ++g)
        for (int a = 0; a < 3; ++a) {
          const int row = 3 * r + a, column = 3 * c + g;
          values_[9 * static_cast<size_t>(e) + 3 * g + a] =
              isFixed_[row] || isFixed_[column] ? (owned && row == column ? 1.0 : 0.0)
                                                : K.block[e](a, g);
        }
    }
  }
  check(MatSetValuesCOO(o_->A, values_.data(), INSERT_VALUES), "MatSetValuesCOO");
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

void LinearSolver::setNearNullSpace() {
  const size_t n = scale_.size(), blocks = n / 3;
  // The centre of every rank's nodes.
  double sums[4] = {0, 0, 0, static_cast<double>(blocks)};
  for (size_t r = 0; r < blocks; ++r)
    for (int a = 0; a < 3; ++a) sums[a] += coordinates_[3 * r + a];
  collective::sum(sums, 4);
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
    const auto dot = [n](const std::vector<double>& a, const std::vector<double>& b) {
      double d = 0;
      for (size_t i = 0; i < n; ++i) d += a[i] * b[i];
      return collective::sum(d);
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

LinearSolve LinearSolver::run(const std::vector<double>& b, double relativeTolerance,
                              bool newPreconditioner, std::vector<double>& x) {
  if (newPreconditioner) setNearNullSpace();
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

LinearSolve LinearSolver::solve(const BlockMatrix& K, const std::vector<double>& b,
                                double relativeTolerance, std::vector<double>& x) {
  setMatrix(K);
  LinearSolve s = run(b, relativeTolerance, freshIterations_ < 0, x);
  if (s.newPreconditioner) {
    freshIterations_ = s.iterations;
  } else if (!s.converged) {
    const int spent = s.iterations;
    s = run(b, relativeTolerance, true, x);
    freshIterations_ = s.iterations;
    s.iterations += spent;
  } else if (s.iterations > kReusedPreconditionerSlowdown * std::max(freshIterations_, 5)) {
    freshIterations_ = -1;
  }
  return s;
}

}  // namespace anode
