#include "Components/MPM/Implicit/LinearSolver.h"

#include <petscksp.h>

#include <stdexcept>

#include "Core/Parallel/Communicator.h"

namespace anode {

namespace {

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

// Owns one PETSc object of each kind the solve makes.
struct Objects {
  Mat A = nullptr;
  Vec x = nullptr, b = nullptr, coordinates = nullptr;
  MatNullSpace rigid = nullptr;
  KSP ksp = nullptr;
  ~Objects() {
    KSPDestroy(&ksp);
    MatNullSpaceDestroy(&rigid);
    VecDestroy(&coordinates);
    VecDestroy(&b);
    VecDestroy(&x);
    MatDestroy(&A);
  }
};

void assemble(const BlockMatrix& K, Mat A) {
  const int n = K.rows();
  std::vector<PetscInt> perRow(3 * static_cast<size_t>(n));
  for (int r = 0; r < n; ++r)
    for (int a = 0; a < 3; ++a) perRow[3 * r + a] = 3 * (K.rowStart[r + 1] - K.rowStart[r]);
  check(MatSeqAIJSetPreallocation(A, 0, perRow.data()), "MatSeqAIJSetPreallocation");
  std::vector<PetscScalar> values;
  for (int r = 0; r < n; ++r) {
    const int begin = K.rowStart[r], count = K.rowStart[r + 1] - begin;
    values.resize(9 * static_cast<size_t>(count));
    // One block row, row-major: (3 x 3 count).
    for (int j = 0; j < count; ++j)
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) values[a * 3 * count + 3 * j + c] = K.block[begin + j](a, c);
    const PetscInt row = r;
    check(MatSetValuesBlocked(A, 1, &row, count, K.column.data() + begin, values.data(),
                              INSERT_VALUES),
          "MatSetValuesBlocked");
  }
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

}  // namespace

LinearSolve solveLinearSystem(const BlockMatrix& K, const std::vector<double>& b,
                              const std::vector<int>& fixed, const std::vector<double>& coordinates,
                              double relativeTolerance, std::vector<double>& x) {
  static_assert(sizeof(PetscInt) == sizeof(int), "PETSc with 32-bit indices");
  startPetsc();
  const PetscInt n = 3 * K.rows();
  Objects o;
  check(MatCreate(PETSC_COMM_SELF, &o.A), "MatCreate");
  check(MatSetSizes(o.A, n, n, n, n), "MatSetSizes");
  check(MatSetType(o.A, MATSEQAIJ), "MatSetType");
  check(MatSetBlockSize(o.A, 3), "MatSetBlockSize");
  assemble(K, o.A);

  check(VecCreateSeq(PETSC_COMM_SELF, n, &o.b), "VecCreateSeq");
  check(VecDuplicate(o.b, &o.x), "VecDuplicate");
  double* bb = nullptr;
  check(VecGetArray(o.b, &bb), "VecGetArray");
  std::copy(b.begin(), b.end(), bb);
  for (int i : fixed) bb[i] = 0;
  check(VecRestoreArray(o.b, &bb), "VecRestoreArray");
  // Fixed components: identity rows and columns scaled like the matrix's diagonal.
  double diagonal = 0;
  for (int r = 0; r < K.rows(); ++r)
    for (int j = K.rowStart[r]; j < K.rowStart[r + 1]; ++j)
      if (K.column[j] == r) diagonal += K.block[j].trace();
  diagonal = n > 0 ? diagonal / n : 1;
  check(MatZeroRowsColumns(o.A, static_cast<PetscInt>(fixed.size()), fixed.data(), diagonal,
                           nullptr, nullptr),
        "MatZeroRowsColumns");

  check(VecCreateSeq(PETSC_COMM_SELF, n, &o.coordinates), "VecCreateSeq");
  check(VecSetBlockSize(o.coordinates, 3), "VecSetBlockSize");
  double* xc = nullptr;
  check(VecGetArray(o.coordinates, &xc), "VecGetArray");
  std::copy(coordinates.begin(), coordinates.end(), xc);
  check(VecRestoreArray(o.coordinates, &xc), "VecRestoreArray");
  check(MatNullSpaceCreateRigidBody(o.coordinates, &o.rigid), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(o.A, o.rigid), "MatSetNearNullSpace");

  check(KSPCreate(PETSC_COMM_SELF, &o.ksp), "KSPCreate");
  check(KSPSetOperators(o.ksp, o.A, o.A), "KSPSetOperators");
  check(KSPSetType(o.ksp, KSPGMRES), "KSPSetType");
  check(KSPGMRESSetRestart(o.ksp, 200), "KSPGMRESSetRestart");
  PC pc = nullptr;
  check(KSPGetPC(o.ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  check(KSPSetTolerances(o.ksp, relativeTolerance, 0.0, PETSC_DEFAULT, 2000), "KSPSetTolerances");
  // Symmetric diagonal scaling: nodes a particle's corner just reaches have stiffness 1e-8 of
  // the others', which breaks GMRES down on the unscaled system.
  check(KSPSetDiagonalScale(o.ksp, PETSC_TRUE), "KSPSetDiagonalScale");
  check(KSPSetDiagonalScaleFix(o.ksp, PETSC_TRUE), "KSPSetDiagonalScaleFix");
  check(KSPSetFromOptions(o.ksp), "KSPSetFromOptions");
  check(KSPSolve(o.ksp, o.b, o.x), "KSPSolve");

  LinearSolve s;
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(o.ksp, &iterations), "KSPGetIterationNumber");
  s.iterations = static_cast<int>(iterations);
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(o.ksp, &reason), "KSPGetConvergedReason");
  s.converged = reason > 0;
  s.reason = KSPConvergedReasons[reason];
  const double* xs = nullptr;
  check(VecGetArrayRead(o.x, &xs), "VecGetArrayRead");
  x.assign(xs, xs + n);
  check(VecRestoreArrayRead(o.x, &xs), "VecRestoreArrayRead");
  return s;
}

}  // namespace anode
