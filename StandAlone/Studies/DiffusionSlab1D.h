// 1-D diffusion verification of the paper (§2.2, Eqs. 9-15): a slab 0 <= x <= 1 with c(x,0) = 0,
// SD-Type Dirichlet c = 1 on x- and c = 0 on x+, constant D (`jg`), compared at t = 0.25 with
// Eq. 13, c(x,t) = (1 - x) - (2/pi) sum_{n=1}^{1000} e^{-D pi^2 n^2 t} sin(n pi x) / n.
// One cell thick in y and z (cubic cells of size h), 2 particles per cell along x, mechanics
// made irrelevant (no swelling, zero stress, mechanical dt far above the diffusion dt).
// Shared by the study tool (diffusion_1d_study) and the verification test.
#pragma once

#include <string>
#include <vector>

#include "StandAlone/Driver/RunSummary.h"

namespace anode {

struct DiffusionSlabCase {
  int cells = 20;                       // N = 1/h cells along x
  std::string interpolator = "linear";  // linear, gimp or cpdi
  std::string dirichlet = "particle";   // <MPM><concentration_dirichlet>: particle or nodal
  double diffusivity = 0.1;
  double timestepMultiplier = 0.4;  // dt = 0.4 h^2/(2D), the reference's choice
  double endTime = 0.25;
  int fourierTerms = 1000;
  // Admissible range written into the input (<min_concentration>, <max_concentration>). The code
  // stops with a SimulationError when a particle leaves it by more than 1e-6 of its width;
  // [0, 1] is the physical range. A wider range lets a run that overshoots finish, so that its
  // accuracy can be measured (labelled as such in the study).
  double minConcentration = 0, maxConcentration = 1;
  // After every step clamp the particle concentrations to [0, 1], as Uintah HEAD does after its
  // G2P (UINTAH_UPS.md P11). Needs a range wider than [0, 1] to have any effect, since the range
  // check runs inside the step, before the clamp.
  bool clampAfterStep = false;

  double h() const { return 1.0 / cells; }
  // Label of the Dirichlet variant (see setDiffusionSlabVariant).
  std::string variant() const;
  bool wideRange() const { return minConcentration < 0 || maxConcentration > 1; }
};

// steps and finalTime: up to the step that stopped the run, if one did.
struct DiffusionSlabResult : RunSummary {
  std::string variant;
  double h = 0;
  double firstDt =
      0;  // the dt of the first step, = multiplier h^2/(2D) when mechanics is irrelevant
  // false: a SimulationError stopped the run; stopMessage is "stopped: c = <the value out of
  // range> at step <k> (t = ...)" for the range check, else "stopped: " + the error.
  bool completed = false;
  std::string stopMessage;
  // Errors at t = endTime, particle by particle against Eq. 13 at the particle position
  // (e_p of Eq. 14 is (c_exact - c_p)/c_exact, 0 where c_exact = 0). Undefined if !completed.
  double paperNorm = 0;            // Eq. 15: sqrt(sum e_p^2) / N
  double rmsRelative = 0;          // sqrt(sum e_p^2 / N)
  double rmsAbsolute = 0;          // sqrt(sum (c_p - c_exact)^2 / N)
  double interiorRmsAbsolute = 0;  // the same over the particles with 0.1 <= x <= 0.9
  double interiorRmsRelative = 0;  // RMS of e_p over the same particles
  double maxAbsolute = 0;          // max |c_p - c_exact|
  double maxAbsoluteAt = 0;        // x of that particle
  // Particle concentration extremes: over every step of the run (including the state that
  // stopped it) and at the end.
  double minConcentration = 0, maxConcentration = 0;
  double minConcentrationTime = 0, maxConcentrationTime = 0;  // when they were reached
  double finalMinConcentration = 0, finalMaxConcentration = 0;
  double maxDisplacement = 0;  // max |u_p| at the end (0: the mechanics stayed still)
};

// Sets dirichlet, the admissible range and the clamp of `c` from a variant label:
//   particle       <concentration_dirichlet>particle (the default), range [0, 1]: the run stops
//                  (SimulationError) if a particle leaves [0, 1] by more than 1e-6
//   nodal          <concentration_dirichlet>nodal (Uintah's rate), range [0, 1]: the same
//   particle-wide  particle with the range widened to [-1, 2] in the input, so that the run
//   finishes nodal-wide     nodal, range [-1, 2] nodal-clamp    nodal-wide plus Uintah HEAD's clamp
//   of c to [0, 1] after every step
// Throws std::invalid_argument for another label.
void setDiffusionSlabVariant(DiffusionSlabCase& c, const std::string& variant);

// Eq. 13 with `terms` Fourier terms.
double diffusionSlabExact(double x, double t, double D, int terms = 1000);

// The .ups text of one case (the output block is inert: runDiffusionSlab writes nothing).
std::string diffusionSlabInput(const DiffusionSlabCase& c);
// Builds the Simulation in memory and advances to endTime. A SimulationError (the concentration
// range check) is caught and reported in the result (completed = false); input errors propagate.
DiffusionSlabResult runDiffusionSlab(const DiffusionSlabCase& c);

// Cells (1/h) of the full study (the paper's h = 0.1 ... 0.001) and of the quick one (the test).
std::vector<int> diffusionSlabStudyCells();
std::vector<int> diffusionSlabQuickCells();

}  // namespace anode
