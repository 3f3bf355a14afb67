// Stress-driven diffusion on the quasi-static path against a closed form and a 1-D solution of
// the same equations (<diffusion_model type="chemical_potential">, ChemicalPotential.h): a bar of
// length L along x standing on its x- end (Symmetric) under gravity -g x, held laterally by
// Symmetric walls (uniaxial strain), without swelling (eta = 0, <stress_coupling> given), so
// that its stress is the weight above each section whatever c does:
//   sigma_xx(X) = -rho g (L - X),  sigma_h = sigma_xx (1 + nu) / (3 (1 - nu)),
//   tau_h = J sigma_h, J = 1 + sigma_xx / (K + 4G/3),  phi(X) = k tau_h(X),
// X the reference position. c (normalised) starts uniform at c0 and diffuses by
//   dc/dt = d/dX [D dc/dX - D c (1 - c) dphi/dX]
// with no flux through the ends (no flux BC: the lithium is conserved). Its equilibrium is
//   c / (1 - c) = A exp(phi(X)),
// A set by the lithium; before it, the reference is that equation solved by finite volumes on
// 400 cells (central fluxes, c(1 - c) at the faces) with explicit steps at 0.4 of their limit.
#pragma once

#include <string>
#include <vector>

#include "StandAlone/Driver/RunSummary.h"

namespace anode {

struct StressDrivenBarCase {
  int cells = 24;  // along the bar (h = L / cells); the grid holds L + 4 h
  std::string interpolator = "gimp";
  // Units arbitrary but consistent: L = D = rho g = 1; k = <stress_coupling> / <cmax_RT> = 3, so
  // phi falls by about 1.3 from the top to the base; the moduli keep the strain below 1e-3.
  double length = 1, diffusivity = 1, density = 1, gravity = 1;
  double bulkModulus = 1000, shearModulus = 1000;
  double stressCoupling = 3, cmaxRT = 1;
  double initialConcentration = 0.5;
  double endTime = 3;  // in L^2 / D: 3 is equilibrium (the slowest mode has decayed to 1e-12)
  double maxDt = 0.05;
  // The first step: gravity, and with it phi, enters over it (the reference has phi from t = 0),
  // so a first step of maxDt would leave an error of order maxDt.
  double firstDt = 1e-6;
  int threads = 0;  // OpenMP threads for the run (0: the OpenMP default)

  // phi at reference position X (the closed form's stress).
  double stressPotential(double X) const;
};

// The equilibrium c(X) holding the lithium of the uniform c0.
class StressDrivenBarEquilibrium {
 public:
  explicit StressDrivenBarEquilibrium(const StressDrivenBarCase& c);
  double concentration(double X) const;

 private:
  StressDrivenBarCase case_;
  double logA_ = 0;
};

// The finite-volume solution at the case's end time.
class StressDrivenBarReference {
 public:
  explicit StressDrivenBarReference(const StressDrivenBarCase& c, int cells = 400);
  double concentration(double X) const;  // linear between cell centres

 private:
  double h_;
  std::vector<double> c_;
};

struct StressDrivenBarResult : RunSummary {
  double h = 0;
  // Against the closed form's equilibrium (at the end time >= 3) or the finite-volume solution:
  // the largest and the mean |c_p - c(X_p)| over the particles.
  double largestError = 0, meanError = 0;
  double concentrationRange = 0;  // max c - min c of the particles
  long newtonIterations = 0;
};

std::string stressDrivenBarInput(const StressDrivenBarCase& c);
// Runs the case and measures it against `equilibrium` (the closed form) or the reference.
StressDrivenBarResult runStressDrivenBar(const StressDrivenBarCase& c, bool equilibrium);

}  // namespace anode
