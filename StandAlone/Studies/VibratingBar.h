// Axial vibrating bar (Bardenhagen 2002 style), the mechanics verification problem: a fixed-free
// elastic bar of length L along x, one cell thick in y and z with Symmetric faces there (uniaxial
// strain, wave modulus M = K + 4G/3, c = sqrt(M/rho)), fixed by a Velocity Dirichlet [0,0,0] on
// x- and free at x = L inside the grid. Initial velocity v(X,0) = v0 sin(pi X/(2L)), zero stress.
// Small-amplitude solution: v(X,t) = v0 cos(wt) sin(pi X/(2L)), w = pi c/(2L), so the centre of
// mass moves with v_cm(t) = (2 v0/pi) cos(wt). Shared by the study tool and the verification test.
#pragma once

#include <string>
#include <vector>

#include "StandAlone/Driver/RunSummary.h"

namespace anode {

struct VibratingBarCase {
  int cells = 16;                       // cells along the bar (the grid extends to ~1.25 L)
  std::string interpolator = "linear";  // linear, gimp or cpdi
  double timestepMultiplier = 0.2;
  double amplitudeRatio = 1e-4;  // v0 / c
  double periods = 1;            // run length in periods T = 2 pi / w
  // > 0: implicit dynamics (<dynamic>true, Newmark), steps of T / implicitStepsPerPeriod;
  // 0: explicit, dt = timestepMultiplier h / (c + |v|).
  int implicitStepsPerPeriod = 0;
  // Material and geometry (SI): c = sqrt((K + 4G/3)/rho) = 100 m/s, T = 4L/c = 0.04 s.
  double length = 1, density = 1000, bulkModulus = 6e6, shearModulus = 3e6;

  double waveSpeed() const;
  double omega() const;
  double period() const;
};

// Errors are relative. Explicit MPM updates v with the stress of the step's start and then the
// stress with the new v (symplectic Euler): a particle velocity after the step ending at t^n is a
// leapfrog half-step value, v(t^n - dt/2) + O(dt^2). Each metric is therefore given twice: as the
// project defines it (velocity taken at t^n, kinetic + strain energy at t^n), which carries an
// O(dt) term, and staggered (exact solution at t^n - dt/2; the leapfrog energy below), which
// isolates the spatial error.
struct VibratingBarResult : RunSummary {
  // max over t = 0 and every step of |v_cm - (2 v0/pi) cos(w t^n)| / (2 v0/pi)
  double centreOfMassError = 0;
  // the same against (2 v0/pi) cos(w (t^n - dt/2)), dt the step just taken
  double centreOfMassErrorStaggered = 0;
  // at the end: sqrt(sum m |v - v(X,t) e_x|^2 / sum m (v0 sin(pi X/2L))^2), X = x - displacement
  double velocityL2Error = 0;
  // max over every step of |E - E0| / E0, E = sum m|v|^2/2 + V (p^2/(2K) + s:s/(4G))
  double energyDrift = 0;
  // the same for the leapfrog energy sum m v^n.v^{n+1}/2 + strain energy at t^n, conserved by
  // the time integrator for a linear problem (drift from geometric nonlinearity, ~ v0/c)
  double leapfrogEnergyDrift = 0;
  // max over the run of |v_y|, |v_z| over v0 (zero in uniaxial strain)
  double transverseVelocity = 0;
};

// The .ups text of one case (no output is written when run through runVibratingBar).
std::string vibratingBarInput(const VibratingBarCase& c);
// Builds the Simulation in memory, sets the initial velocity, advances to the end time and
// samples every step. Throws what the Simulation throws.
VibratingBarResult runVibratingBar(const VibratingBarCase& c);

// Resolutions (cells along the bar) of the full study and of the quick one used by the test.
std::vector<int> vibratingBarStudyCells();
std::vector<int> vibratingBarQuickCells();

}  // namespace anode
