// Newton's method for the equilibrium step (EquilibriumSolver.h): the loop of iterations, its
// inexact linear solves, the line search, the prediction's first iterate and ImpMPM's convergence
// test. The unknowns' numbering is EquilibriumNumbering.cc's, the residual and Jacobian
// EquilibriumAssembly.cc's.
#include "Components/MPM/Implicit/EquilibriumSolver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "Components/MPM/Implicit/LineSearch.h"
#include "Components/MPM/Implicit/Newmark.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"
#include "Core/Util/StepActivity.h"

namespace anode {

namespace {

// Newton's linear solves are inexact (Eisenstat and Walker's second choice): the relative residual
// of iteration k's solve is 0.9 (|r_k| / |r_k-1|)^2, within [kLinearToleranceLeast,
// kLinearToleranceMost], and kLinearToleranceMost in the first iteration. Early iterations, far
// from the equilibrium, need no accurate correction; the last ones are solved to 1e-9.
constexpr double kLinearToleranceMost = 1e-1, kLinearToleranceLeast = 1e-9;
// The first iteration from a solved prediction taken (EquilibriumProblem::predictedIsSolved, the
// trapezoidal step's own solve): the iterate is near the equilibrium, where a correction to 0.1
// wastes the iteration. The large pillar's cycle, steps 13-14 from its step-12 checkpoint: 16
// Newton iterations with 3e-3 or 1e-3 (in the predictions' first iterations too), 18 with 1e-2,
// 20 with 0.1. Not from the last step's motion, an extrapolation: Figure 4's pillar with 3e-3
// there took 171 Newton and 1,717 Krylov iterations against 167 and 1,521.
constexpr double kLinearToleranceFromSolvedPrediction = 3e-3;

// <jacobian_reuse>: Newton keeps the Jacobian of its last iteration (K and the linear solver's
// matrix as they are) for the next correction when the last correction was small and came fast: its
// |du|^2 ratio below kKeptTangentRatio and at most kKeptTangentContraction of the one before (the
// first's measured against 1). Then the Jacobian changes by O(|du|) of the step while the next
// correction is smaller still, and the iteration costs the residual and a linear solve, not the
// particles' tangents. Far from the equilibrium, or when Newton slowed, the tangent is assembled
// anew. The large pillar's cycle, steps 13-14 from the step-12 checkpoint (ratios of its own
// solves 4.7e-3, 1.5e-4, 3.2e-7 and 5.6e-3, 4.5e-5, 2.1e-6): 12 Newton iterations, 8 of them
// with a new Jacobian (the last of each solve kept it), as many as without the rule; with 1e-2
// instead (keeping it after the own solve's first correction, 7.5e-3) the second step took 17
// iterations instead of 3.
constexpr double kKeptTangentRatio = 1e-3, kKeptTangentContraction = 0.1;

bool keepsTangentOfLastIteration(const std::vector<std::pair<double, double>>& ratios) {
  const double last = ratios.back().first;
  const double before = ratios.size() > 1 ? ratios[ratios.size() - 2].first : 1.0;
  return last < kKeptTangentRatio && last <= kKeptTangentContraction * before;
}

}  // namespace

void EquilibriumSolver::useTimers(TaskTimers& timers) {
  timers_ = &timers;
  assemblyTask_ = timers.task("assembleEquilibrium");
  solveTask_ = timers.task("solveLinearSystem");
}

void EquilibriumSolver::startFromPrescribed(const EquilibriumProblem& problem) {
  u_.assign(row_.size(), std::vector<Vec3>(problem.grid.numNodes(), Vec3::Zero()));
  for (size_t f = 0; f < row_.size(); ++f)
    for (int k = 0; k < problem.grid.numNodes(); ++k)
      for (int a = 0; a < 3; ++a)
        if (!std::isnan(problem.prescribed[f][k][a])) u_[f][k][a] = problem.prescribed[f][k][a];
}

void EquilibriumSolver::addToDisplacement(const std::vector<double>& du, double scale) {
  for (size_t r = 0; r < unknown_.size(); ++r) {
    const auto [f, k] = unknown_[r];
    u_[f][k] += scale * Vec3(du[3 * r], du[3 * r + 1], du[3 * r + 2]);
  }
}

bool EquilibriumSolver::takeStep(Collective every, const EquilibriumProblem& problem, double dt,
                                 double stabilization, const std::vector<double>& du,
                                 double residualNorm, double energy) {
  std::optional<ScopedTimer> s;
  if (timers_) s.emplace(*timers_, assemblyTask_);
  double at = 0, norm = 0;
  const auto moveTo = [&](double fraction) {
    addToDisplacement(du, fraction - at);
    at = fraction;
    assemble(every, problem, dt, stabilization, false);
    norm = ownedDot(every, residual_, residual_);
  };
  const auto slope = [&] {
    return std::isfinite(norm) ? ownedDot(every, du, residual_)
                               : std::numeric_limits<double>::quiet_NaN();
  };
  moveTo(1.0);
  // The whole correction lowers the residual's norm (false for NaN), or round-off hides the
  // energy's slope (du.r(u) <= 0 within the linear solve's error) and its residual is a number:
  // it is taken. Otherwise the search along it (LineSearch.h).
  if (norm < residualNorm || (!(energy > 0) && std::isfinite(norm))) return true;
  const LineSearchChoice choice = searchAlongCorrection(
      std::max(energy, std::numeric_limits<double>::min()), slope(), [&](double fraction) {
        moveTo(fraction);
        return slope();
      });
  if (choice.lastTried) return true;
  addToDisplacement(du, choice.fraction - at);
  return false;
}

bool EquilibriumSolver::tryPrediction(Collective every, const EquilibriumProblem& problem,
                                      double dt, double stabilization, double& normReference,
                                      double& energyReference) {
  if (problem.predicted.empty()) return false;
  std::optional<ScopedTimer> s;
  if (timers_) s.emplace(*timers_, assemblyTask_);
  std::vector<double> step(residual_.size(), 0.0);
  for (size_t r = 0; r < unknown_.size(); ++r) {
    const auto [f, k] = unknown_[r];
    for (int a = 0; a < 3; ++a)
      if (std::isnan(problem.prescribed[f][k][a])) step[3 * r + a] = problem.predicted[f][k][a];
  }
  const double startNorm = ownedDot(every, residual_, residual_);
  const double size = ownedDot(every, step, step),
               work = std::abs(ownedDot(every, step, residual_));
  if (!(size > 0)) return false;
  std::vector<double> startResidual = residual_;
  addToDisplacement(step, 1.0);
  assemble(every, problem, dt, stabilization, false);
  if (ownedDot(every, residual_, residual_) < startNorm) {  // false for NaN
    normReference = size;
    energyReference = work;
    return true;
  }
  addToDisplacement(step, -1.0);
  residual_ = std::move(startResidual);
  return false;
}

void EquilibriumSolver::computeEndOfStepAcceleration(const EquilibriumProblem& problem, double dt) {
  acceleration_.assign(row_.size(), std::vector<Vec3>(problem.grid.numNodes(), Vec3::Zero()));
  for (const auto& [f, k] : unknown_)
    acceleration_[f][k] =
        newmarkAcceleration(u_[f][k], problem.velocity[f][k], problem.acceleration[f][k], dt);
}

NewtonReport EquilibriumSolver::solve(Collective every, const EquilibriumProblem& problem,
                                      double dt, const ImplicitOptions& options) {
  std::optional<ScopedTimer> setUp;
  if (timers_) setUp.emplace(*timers_, assemblyTask_);
  // A kept solver's unknowns and pattern are this solve's, and so are its solve's last tangent
  // and the hourglass stiffness of the same start: the first iteration assembles the residual.
  const bool solverKept = takesKeptLinearSolver(every, problem);
  if (!solverKept) numberUnknowns(every, problem, options.jacobianCouplingShare);
  startFromPrescribed(problem);
  const bool tangentKept = solverKept && !kept_.block.empty();
  if (tangentKept) {
    K_.block = std::move(kept_.block);
    hourglass_ = std::move(kept_.hourglass);
    hourglassTangent_ = std::move(kept_.hourglassTangent);
    hourglassLoad_ = std::move(kept_.hourglassLoad);
  }
  kept_ = KeptTangent{};  // freed before a new K's values are allocated
  if (!tangentKept) {
    K_.block.assign(K_.column.size(), Mat3::Zero());
    hourglass_.clear();
    hourglassTangent_.clear();
  }
  if (!solverKept) {
    try {
      buildLinearSolver(every, problem);
    } catch (const LibraryFailure& e) {
      throw LibraryFailure(std::string("setting up the linear solver: ") + e.what());
    }
  }
  setUp.reset();
  // Every return frees the linear solver unless the next solve is to take it.
  struct Release {
    std::unique_ptr<LinearSolver>& solver;
    bool keep;
    ~Release() {
      if (!keep) solver.reset();
    }
  } release{linearSolver_, problem.keepLinearSolver};
  NewtonReport report;
  double normMax = 0, qNorm0 = 0, lastResidualNorm = 0;
  std::vector<double> du;
  bool residualCurrent = false;  // residual_ is at u (the line search's accepted trial)
  while (true) {
    if (report.iterations >= options.maxIterations) {
      report.failure = "no convergence in " + std::to_string(options.maxIterations) +
                       " iterations (<iters_before_timestep_restart>)";
      return report;
    }
    collective::stopIfRequested(every);  // a stop drops the step between iterations
    ++report.iterations;
    noteStepActivity(0, "Newton iteration", report.iterations);
    const bool keepTangent =
        report.iterations == 1
            ? tangentKept
            : options.jacobianReuse && keepsTangentOfLastIteration(report.ratios);
    if (!(keepTangent && residualCurrent)) {
      std::optional<ScopedTimer> s;
      if (timers_) s.emplace(*timers_, assemblyTask_);
      assemble(every, problem, dt, options.hourglassStabilization, !keepTangent);
    }
    if (!keepTangent) ++report.newTangents;
    bool fromSolvedPrediction = false;
    if (report.iterations == 1)
      fromSolvedPrediction =
          tryPrediction(every, problem, dt, options.hourglassStabilization, normMax, qNorm0) &&
          problem.predictedIsSolved;
    const double residualNorm = ownedDot(every, residual_, residual_);
    const double tolerance =
        report.iterations == 1
            ? (fromSolvedPrediction ? kLinearToleranceFromSolvedPrediction : kLinearToleranceMost)
            : std::clamp(0.9 * residualNorm / lastResidualNorm, kLinearToleranceLeast,
                         kLinearToleranceMost);
    lastResidualNorm = residualNorm;
    report.linearTolerances.push_back(tolerance);
    LinearSolve linear;
    {
      std::optional<ScopedTimer> s;
      if (timers_) s.emplace(*timers_, solveTask_);
      try {
        linear = linearSolver_->solve(every, K_, residual_, tolerance, du, !keepTangent);
      } catch (const LibraryFailure& e) {
        throw LibraryFailure("the linear solve of Newton iteration " +
                             std::to_string(report.iterations) + ": " + e.what());
      }
      du.resize(residual_.size());
      completeOverRanks(every, problem, du, 3, true);
    }
    report.krylovIterations += linear.iterations;
    if (linear.newPreconditioner) ++report.preconditionerSetUps;
    if (!linear.converged) {
      report.failure = "the linear solve did not converge (" + linear.reason + ", " +
                       std::to_string(linear.iterations) + " iterations)";
      return report;
    }
    removeRigidMotionOfFreeBodies(every, problem, du);
    const double norm = ownedDot(every, du, du), qNorm = ownedDot(every, du, residual_);
    normMax = std::max(normMax, norm);
    if (report.iterations == 1) qNorm0 = std::max(qNorm0, std::abs(qNorm));
    // The ratios measure the whole correction, the distance Newton still sees to the
    // equilibrium, whatever fraction of it the line search takes.
    const double dispRatio = norm / (normMax + 1e-100), energyRatio = qNorm / (qNorm0 + 1e-100);
    report.ratios.emplace_back(dispRatio, energyRatio);
    if (!std::isfinite(dispRatio) || !std::isfinite(energyRatio)) {
      report.failure = "a residual that is not a number";
      return report;
    }
    // du.r = du.K du up to the linear solve's error: a negative du.r beyond that error shows K
    // is not positive along du; within it, |du.r| is what the energy test measures.
    if (qNorm < -linear.energySlack) {
      report.failure = "a negative energy norm du.r (the Jacobian is not positive there)";
      return report;
    }
    const bool dispDone =
        dispRatio <= options.convergenceDisp || normMax <= options.convergenceDisp;
    const bool energyDone =
        std::abs(energyRatio) <= options.convergenceEnergy || qNorm0 <= options.convergenceEnergy;
    if (dispDone && energyDone) {
      // The last correction is taken whole: within Newton's tolerance the line search has
      // nothing to choose.
      addToDisplacement(du, 1.0);
      report.converged = true;
      if (problem.keepLinearSolver)
        kept_ = KeptTangent{std::move(K_.block), std::move(hourglass_),
                            std::move(hourglassTangent_), std::move(hourglassLoad_)};
      if (!problem.velocity.empty()) computeEndOfStepAcceleration(problem, dt);
      return report;
    }
    residualCurrent =
        takeStep(every, problem, dt, options.hourglassStabilization, du, residualNorm, qNorm);
  }
}

}  // namespace anode
