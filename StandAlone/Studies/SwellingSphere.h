// A quasi-static problem with a non-uniform closed form: a free linear-elastic sphere of radius b
// with a fixed radial concentration profile c(r) = c_s (r/b)^2 (the quasi-steady shape under a
// constant surface flux) and the linear swelling strain eta c on each axis: the thermoelastic
// sphere of Timoshenko & Goodier (Theory of Elasticity, 3rd ed., Sec. 151) with alpha T -> eta c.
// With beta = eta c_s, nu Poisson's ratio and E Young's modulus:
//   u(r)     = beta / (5 (1 - nu)) [(1 + nu) r^3 / b^2 + 2 (1 - 2 nu) r],
//   sigma_rr = 2 beta E / (5 (1 - nu)) (1 - r^2/b^2),
//   sigma_tt = beta E / (5 (1 - nu)) (2 - 4 r^2/b^2)   (both tangential directions).
// The body is an octant (Symmetric faces x-, y-, z- through the centre), filled by <res> particles
// per cell and axis on a grid of N cells per radius, rf_elastic_plastic without a flow model.
// The concentration enters as the stress it causes with F held at I, which is where
// rf_elastic_plastic's swelling rate (eta dc/dt on each normal rate) takes a body whose c rises
// to c(r): sigma_0 = -3 K beta (r/b)^2 I, set on the particles before the first step. The run
// then relaxes it to equilibrium: one implicit step, or explicit steps with grid damping until
// the sphere's vibration has died out. Shared by the study tool and the verification test.
#pragma once

#include <string>
#include <vector>

#include "StandAlone/Driver/RunSummary.h"

namespace anode {

struct SwellingSphereCase {
  int cells = 8;                        // N, cells per radius (h = b/N)
  std::string interpolator = "linear";  // linear, gimp or cpdi
  std::string integrator = "implicit";  // implicit (one quasi-static step) or explicit
  int particlesPerCell = 2;             // per axis
  // Implicit only: <hourglass_stabilization> (negative: the input's default, 0.1).
  double hourglassStabilization = -1;
  // Units arbitrary but consistent (nm and GPa, say): silicon's moduli, nu = 0.2996. Newton's
  // convergence test (ImpMPM's) also stops when the largest |du|^2 of the step or the first
  // du.r is itself below its criterion (1e-10, 4e-10): with b = 1000 and beta = 1e-6 both are
  // orders of magnitude above, so that the relative tests decide.
  double radius = 1000, bulkModulus = 67, shearModulus = 31;
  double surfaceStrain = 1e-6;  // beta = eta c_s: small, so that linear theory holds
  // Explicit only: density, grid damping a -= coeff v (<artificial_damping_coeff>; the study
  // and the test take 5 c/b), run length (needed) and timestep multiplier.
  double density = 1, damping = 0, endTime = 0, timestepMultiplier = 0.5;
  int threads = 0;  // OpenMP threads for the run (0: the OpenMP default)

  double youngsModulus() const;
  double poissonsRatio() const;
  double waveSpeed() const;  // sqrt((K + 4G/3)/rho)
};

// The closed form at radius r (r <= b).
struct SwellingSphereExact {
  double radialDisplacement, radialStress, hoopStress;
};
SwellingSphereExact swellingSphereExact(const SwellingSphereCase& c, double r);

struct SwellingSphereResult : RunSummary {
  std::string integrator;
  double h = 0;
  // Volume-weighted relative L2 errors over the particles, the exact values at each particle's
  // initial radius: sqrt(sum V (q_p - q(r_p))^2 / sum V q(r_p)^2).
  double radialDisplacementError = 0, radialStressError = 0, hoopStressError = 0;
  // max_p |displacement - its radial part| / max_p |u(r_p)|: zero for the exact solution.
  double tangentialDisplacement = 0;
  long newtonIterations = 0, krylovIterations = 0;  // implicit only
  // Per particle, in particle order: initial radius, u_r, sigma_rr, sigma_tt (the mean of the
  // two tangential normal stresses).
  std::vector<double> r, ur, srr, stt;
};

// The .ups text of one case (no initial stress: that is set on the particles by the run).
std::string swellingSphereInput(const SwellingSphereCase& c);
// Builds the Simulation in memory, sets sigma_0, runs it to its end and measures.
SwellingSphereResult runSwellingSphere(const SwellingSphereCase& c);

// Relative L2 difference of two runs' fields (same case but the integrator), volume weights
// taken as equal: sqrt(sum (a - b)^2 / sum b^2).
double relativeDifference(const std::vector<double>& a, const std::vector<double>& b);

std::vector<int> swellingSphereStudyCells();
std::vector<int> swellingSphereQuickCells();

}  // namespace anode
