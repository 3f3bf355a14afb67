// A PETSc failure in a step is a diagnostic stop (exit 3) that names the step and the phase, on
// one process and on two ranks (the one-command mode), where the rank that found it ends the
// others instead of leaving them in PETSc's collectives.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/RunSus.h"

namespace anode {
namespace {

namespace fs = std::filesystem;

// PETSC_OPTIONS asking for a factorization PETSc does not have: the preconditioner's set-up in
// the first Krylov solve fails on every rank.
struct BrokenPetsc {
  BrokenPetsc() {
    setenv("PETSC_OPTIONS", "-pc_type lu -pc_factor_mat_solver_type nonexistent", 1);
  }
  ~BrokenPetsc() { unsetenv("PETSC_OPTIONS"); }
};

void expectDiagnosticStop(const std::vector<std::string>& mode, const std::string& name,
                          bool severalRanks) {
  const fs::path dir = fs::temp_directory_path() / ("anode_library_failure_" + name);
  fs::remove_all(dir);
  std::vector<std::string> args = mode;
  for (const std::string& a :
       {std::string("-o"), dir.string(),
        std::string(ANODE_SOURCE_DIR) + "/inputs/Stability/Implicit_contact_null.ups"})
    args.push_back(a);
  const BrokenPetsc broken;
  const testing::SusResult run = testing::runSus(args);
  EXPECT_EQ(run.exitCode, 3) << run.output;
  EXPECT_NE(run.output.find("step 1, t = "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("the linear solve of Newton iteration 1: PETSc's KSPSolve failed"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("nonexistent"), std::string::npos) << run.output;  // PETSc's words
  if (severalRanks) {
    EXPECT_NE(run.output.find("sus: simulation stopped on rank "), std::string::npos) << run.output;
  } else {
    // One process stops as after any diagnostic: the last good state written.
    EXPECT_NE(run.output.find("sus: simulation stopped: "), std::string::npos) << run.output;
    EXPECT_TRUE(fs::exists(dir / "particles.pvd")) << run.output;
  }
  fs::remove_all(dir);
}

TEST(LibraryFailure, PetscFailingInAStepStopsOneProcessWithItsStepAndPhase) {
  expectDiagnosticStop({"--one-process", "--threads", "1"}, "one_process", false);
}

TEST(LibraryFailure, PetscFailingInAStepEndsEveryRankWithExitCode3) {
  expectDiagnosticStop({"--threads", "2"}, "two_ranks", true);
}

}  // namespace
}  // namespace anode
