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
  Vec x = nullptr, b = nullptr;
  KSP ksp = nullptr;
  ~Objects() {
    KSPDestroy(&ksp);
    VecDestroy(&b);
    VecDestroy(&x);
    MatDestroy(&A);
  }
};

LinearSolver::LinearSolver(const BlockMatrix& pattern, std::vector<int> fixed,
                           std::vector<double> coordinates)
    : o_(std::make_unique<Objects>()),
      fixed_(std::move(fixed)),
      coordinates_(std::move(coordinates)) {
  static_assert(sizeof(PetscInt) == sizeof(int), "PETSc with 32-bit indices");
  startPetsc();
  const int blocks = pattern.rows();
  const PetscInt n = 3 * blocks;
  isFixed_.assign(static_cast<size_t>(n), 0);
  for (int i : fixed_) isFixed_[i] = 1;
  check(MatCreate(PETSC_COMM_SELF, &o_->A), "MatCreate");
  check(MatSetSizes(o_->A, n, n, n, n), "MatSetSizes");
  check(MatSetType(o_->A, MATSEQAIJ), "MatSetType");
  check(MatSetBlockSize(o_->A, 3), "MatSetBlockSize");
  std::vector<PetscInt> perRow(static_cast<size_t>(n));
  for (int r = 0; r < blocks; ++r)
    for (int a = 0; a < 3; ++a)
      perRow[3 * r + a] = 3 * (pattern.rowStart[r + 1] - pattern.rowStart[r]);
  check(MatSeqAIJSetPreallocation(o_->A, 0, perRow.data()), "MatSeqAIJSetPreallocation");
  // The pattern: every 3 x 3 block of K, zeros included.
  std::vector<PetscScalar> zeros;
  for (int r = 0; r < blocks; ++r) {
    const int begin = pattern.rowStart[r], count = pattern.rowStart[r + 1] - begin;
    zeros.assign(9 * static_cast<size_t>(count), 0.0);
    const PetscInt row = r;
    check(MatSetValuesBlocked(o_->A, 1, &row, count, pattern.column.data() + begin, zeros.data(),
                              INSERT_VALUES),
          "MatSetValuesBlocked");
  }
  check(MatAssemblyBegin(o_->A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(o_->A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  checkLayout(pattern);
  check(VecCreateSeq(PETSC_COMM_SELF, n, &o_->b), "VecCreateSeq");
  check(VecDuplicate(o_->b, &o_->x), "VecDuplicate");
  check(KSPCreate(PETSC_COMM_SELF, &o_->ksp), "KSPCreate");
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
  // Symmetric diagonal scaling, D K D with D = |diag K|^-1/2: nodes a particle's corner just
  // reaches have stiffness 1e-8 of the others', which breaks GMRES down on the unscaled system.
  const int blocks = K.rows();
  scale_.assign(3 * static_cast<size_t>(blocks), 1.0);
  for (int r = 0; r < blocks; ++r)
    for (int j = K.rowStart[r]; j < K.rowStart[r + 1]; ++j)
      if (K.column[j] == r)
        for (int a = 0; a < 3; ++a)
          if (K.block[j](a, a) != 0) scale_[3 * r + a] = 1 / std::sqrt(std::abs(K.block[j](a, a)));
  PetscScalar* values = nullptr;
  check(MatSeqAIJGetArray(o_->A, &values), "MatSeqAIJGetArray");
#pragma omp parallel for schedule(static)
  for (int r = 0; r < blocks; ++r) {
    const int begin = K.rowStart[r], count = K.rowStart[r + 1] - begin;
    for (int a = 0; a < 3; ++a) {
      const int row = 3 * r + a;
      PetscScalar* v = values + valueOffset(K, r, a);  // (row, 3 K.column[begin] + 0), ...
      for (int j = 0; j < count; ++j)
        for (int g = 0; g < 3; ++g) {
          const int column = 3 * K.column[begin + j] + g;
          if (isFixed_[row] || isFixed_[column])
            v[3 * j + g] = row == column ? 1.0 : 0.0;
          else
            v[3 * j + g] = scale_[row] * K.block[begin + j](a, g) * scale_[column];
        }
    }
  }
  check(MatSeqAIJRestoreArray(o_->A, &values), "MatSeqAIJRestoreArray");
}

size_t LinearSolver::valueOffset(const BlockMatrix& K, int r, int a) {
  const size_t count = K.rowStart[r + 1] - K.rowStart[r];
  return 9 * static_cast<size_t>(K.rowStart[r]) + 3 * count * a;
}

void LinearSolver::checkLayout(const BlockMatrix& pattern) {
  PetscInt n = 0;
  const PetscInt *start = nullptr, *column = nullptr;
  PetscBool done = PETSC_FALSE;
  check(MatGetRowIJ(o_->A, 0, PETSC_FALSE, PETSC_FALSE, &n, &start, &column, &done), "MatGetRowIJ");
  bool same = done && n == 3 * pattern.rows();
  for (int r = 0; same && r < pattern.rows(); ++r)
    for (int a = 0; a < 3 && same; ++a) {
      const size_t offset = valueOffset(pattern, r, a);
      same = static_cast<size_t>(start[3 * r + a]) == offset;
      for (int j = pattern.rowStart[r]; same && j < pattern.rowStart[r + 1]; ++j)
        for (int g = 0; g < 3; ++g)
          same = same &&
                 column[offset + 3 * (j - pattern.rowStart[r]) + g] == 3 * pattern.column[j] + g;
    }
  check(MatRestoreRowIJ(o_->A, 0, PETSC_FALSE, PETSC_FALSE, &n, &start, &column, &done),
        "MatRestoreRowIJ");
  if (!same)
    throw std::runtime_error("PETSc: the AIJ matrix does not hold K's blocks in K's order");
}

void LinearSolver::setNearNullSpace() {
  const size_t n = scale_.size(), blocks = n / 3;
  Vec3 centre = Vec3::Zero();
  for (size_t r = 0; r < blocks; ++r)
    centre += Vec3(coordinates_[3 * r], coordinates_[3 * r + 1], coordinates_[3 * r + 2]);
  if (blocks > 0) centre /= static_cast<double>(blocks);
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
    for (int i : fixed_) m[i] = 0;
    double before = 0;
    for (double v : m) before += v * v;
    // Modified Gram-Schmidt; a mode the fixed components remove is dropped.
    for (const std::vector<double>& q : modes) {
      double dot = 0;
      for (size_t i = 0; i < n; ++i) dot += q[i] * m[i];
      for (size_t i = 0; i < n; ++i) m[i] -= dot * q[i];
    }
    double norm = 0;
    for (double v : m) norm += v * v;
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
  check(MatNullSpaceCreate(PETSC_COMM_SELF, PETSC_FALSE, static_cast<PetscInt>(vectors.size()),
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
  for (int i : fixed_) bb[i] = 0;
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
  const double* xs = nullptr;
  check(VecGetArrayRead(o_->x, &xs), "VecGetArrayRead");
  x.resize(scale_.size());
  for (size_t i = 0; i < scale_.size(); ++i) x[i] = scale_[i] * xs[i];
  check(VecRestoreArrayRead(o_->x, &xs), "VecRestoreArrayRead");
  // The fixed components' rows are decoupled, but an inexact solve leaves round-off of its
  // tolerance on them.
  for (int i : fixed_) x[i] = 0;
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
