// A free elastic sphere lithiated through its surface: the quasi-static path's diffusion and
// swelling together against closed forms. The octant of a sphere of radius b (Symmetric faces
// x-, y-, z- through the centre), c = 0 at the start, takes up lithium at a constant flux J
// through its whole surface (`jg`, constant D), rf_elastic_plastic without a flow model, swelling
// eta c on each axis, in quasi-static steps chosen by their error estimate. Closed forms at the
// run's end t:
//   c(r, t) = (J b / D) [3 D t / b^2 + r^2 / (2 b^2) - 3/10
//             - (2 b / r) sum_n exp(-a_n^2 D t / b^2) sin(a_n r / b) / (a_n^2 sin a_n)],
//   a_n the positive roots of a cot a = 1 (Crank, The Mathematics of Diffusion, 2nd ed., Eq. 6.60);
// and the thermoelastic sphere with eta c(r) for alpha T (Timoshenko & Goodier, Theory of
// Elasticity, 3rd ed., Sec. 151), with I(r) = int_0^r c s^2 ds:
//   sigma_rr = 2 eta E / (1 - nu) [I(b) / b^3 - I(r) / r^3],
//   sigma_tt = eta E / (1 - nu) [2 I(b) / b^3 + I(r) / r^3 - c(r)].
// The surface's flux restriction R(c) = 1 + ln(1 - c)/4 (c below 0.006 here) takes less than
// 0.15% off J. Each <swelling_strain> can be run (docs/quasi-static.md, "Swelling on cells").
// With stress-driven diffusion (`cmaxRT` > 0: <diffusion_model type="chemical_potential">, k =
// 3 eta / cmax_RT), the sphere's mean stress sigma_h = 2 eta E / (3 (1 - nu)) (c_mean - c) (the
// stresses above) makes the flux -D (1 + s c (1 - c)) dc/dr, s = k 2 eta E / (3 (1 - nu)), to
// first order in the strain: c(r, t) is then that nonlinear radial diffusion's, solved by finite
// volumes (400 shells, explicit steps at 0.4 of their limit), and the stresses follow from it as
// above. (The pass's implicit local part, ChemicalPotential.h, is then the whole stress term.)
#pragma once

#include <string>
#include <vector>

#include "StandAlone/Driver/RunSummary.h"

namespace anode {

struct LithiatedSphereCase {
  int cells = 8;                            // N, cells per radius (h = b/N)
  std::string interpolator = "cpdi";        // linear, gimp or cpdi
  int particlesPerCell = 2;                 // per axis
  std::string swellingStrain = "particle";  // particle or cell_mean
  // Units arbitrary but consistent (nm, GPa and a time unit with b^2 / D = 1): silicon's moduli;
  // J b / (2 D) = 0.002, the surface's c above the centre's once the profile is steady, and eta
  // small, so that linear theory holds; b = 1000 so that Newton's relative tests decide.
  double radius = 1000, bulkModulus = 67, shearModulus = 31, expansion = 0.1;
  double diffusivity = 1e6, flux = 4;
  double endTime = 0.4;  // in b^2 / D: the profile's transient has decayed to 3e-4
  // > 0: chemical_potential with this <cmax_RT> (5e-3: s = 460, so D (1 + s c (1 - c)) reaches
  // 3.6 D at the surface); 0: jg.
  double cmaxRT = 0;
  // <error_tolerance>: c stays below 0.006 of c_max = 1, so well below the default 0.01.
  double errorTolerance = 1e-5;
  int threads = 0;  // OpenMP threads for the run (0: the OpenMP default)

  double youngsModulus() const;
  double poissonsRatio() const;
  // s = k 2 eta E / (3 (1 - nu)), k = 3 eta / cmaxRT (cmaxRT > 0).
  double stabilization() const;
};

// The closed forms at radius r <= b at the case's end time.
struct LithiatedSphereExact {
  double concentration, radialStress, hoopStress;
};
class LithiatedSphereSolution {
 public:
  explicit LithiatedSphereSolution(const LithiatedSphereCase& c);
  double concentration(double r) const;
  LithiatedSphereExact at(double r) const;

 private:
  LithiatedSphereCase case_;
  std::vector<double> roots_;              // a_n
  std::vector<double> shells_;             // c of the finite-volume shells (cmaxRT > 0)
  std::vector<double> radius_, integral_;  // I(r) on a fine grid of [0, b]
};

struct LithiatedSphereResult : RunSummary {
  std::string swellingStrain;
  double cmaxRT = 0;
  double h = 0;
  // Volume-weighted relative L2 errors over the particles against the closed forms at each
  // particle's initial radius: sqrt(sum V (q_p - q(r_p))^2 / sum V q(r_p)^2).
  double concentrationError = 0, radialStressError = 0, hoopStressError = 0;
  // The largest |sigma_rr - exact| or |sigma_tt - exact| of a particle over max |sigma_tt exact|.
  double largestStressError = 0;
  long newtonIterations = 0;
};

// The .ups text of one case.
std::string lithiatedSphereInput(const LithiatedSphereCase& c);
// Builds the Simulation in memory, runs it to its end and measures.
LithiatedSphereResult runLithiatedSphere(const LithiatedSphereCase& c);

}  // namespace anode
