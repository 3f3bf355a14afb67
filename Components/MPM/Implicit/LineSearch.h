// Newton's line search on the correction's energy, for the corrections whose whole step raises
// the residual's norm (EquilibriumSolver::takeStep). Along a correction du from u, g(s) = du.r(u +
// s du) is the energy's slope: it falls from g(0) = du.K du > 0 to zero at the energy's minimum
// along du (Matthies and Strang, 1979). The search looks for a fraction s in (0, 1] where |g(s)|
// <= kEnergyReduction g(0), by regula falsi (Illinois: an end kept twice has its g halved), each
// trial within kLineSearchMargin of the bracket's ends.
//
// A trial short of the minimum (0 < g < g(0)) moves the lower end; one past it (g < 0) moves the
// upper end, and so does one where g has risen beyond g(0) (no energy falls so steeply along du:
// the trial left the region the tangent describes, and the secant points to the lower end's
// margin) or is not a number (a trial inverting a particle: the next trial bisects).
//
// Why not the residual's norm: at the whole large pillar's top rim, where both flux BCs meet, its
// first 2-s step's corrections raised the norm 1e5-fold at a few nodes while the energy along du
// fell; halving until the norm fell (1/16 of the correction at most iterations) took 13 + 22
// Newton iterations and 604 Krylov iterations, this search 7 + 8 and 225.
#pragma once

#include <functional>

namespace anode {

constexpr int kLineSearchTrials = 5;
constexpr double kEnergyReduction = 0.5, kLineSearchMargin = 0.05;

struct LineSearchChoice {
  double fraction;  // of the correction, to be taken
  bool lastTried;   // whether it is the last fraction slopeAt was called with
};

// `energy` is g(0) > 0, `wholeSlope` g(1), already evaluated; slopeAt(s) evaluates g(s) (the
// caller moves u to u + s du and assembles the residual there). The fraction of the lowest |g|
// tried when none meets the criterion in kLineSearchTrials trials (the whole one counted).
LineSearchChoice searchAlongCorrection(double energy, double wholeSlope,
                                       const std::function<double(double)>& slopeAt);

}  // namespace anode
