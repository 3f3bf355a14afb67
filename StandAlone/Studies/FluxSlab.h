// Flux boundary condition verification (Carslaw & Jaeger): a slab 0 <= x <= L, initially free of
// lithium, with a constant flux J entering through x = L (a <scalar_flux> box BC on the body's
// x+ face, paper Eqs. 16-18) and every other face insulated (no SD-Type BC), constant D (jg):
//   c(x,t) = J t/L + (J L/D) [ (3x^2 - L^2)/(6 L^2)
//            - (2/pi^2) sum_{n>=1} (-1)^n/n^2 exp(-D n^2 pi^2 t/L^2) cos(n pi x/L) ].
// Mechanics plays no part: no flow model, no swelling, zero velocity, a large density so the
// mechanical dt (Eq. 43) is far above the diffusion dt (Eq. 44). The grid covers [0, L] exactly
// (cells aligned with the body), 2 particles per cell along x, the body one cell thick in y and z
// (or `thickness` cells, with the flux on the whole x+ face). Shared by the study tool and the
// verification test; the same run also accumulates the lithium balance.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "StandAlone/Driver/RunSummary.h"

namespace anode {

struct FluxSlabCase {
  int cells = 16;                       // cells along x (h = L/cells)
  int thickness = 1;                    // cells in y and z
  std::string interpolator = "linear";  // linear, gimp or cpdi
  double timestepMultiplier = 0.2;
  double length = 1;       // L
  double diffusivity = 1;  // D (jg)
  double flux = 1e-6;      // J, normalised concentration x length / time, into the body
  double fourier = 0.25;   // D t_end / L^2
  // Optional piecewise-linear load curve (time, J) replacing the constant `flux` (balance tests);
  // the analytic solution is then not meaningful.
  std::vector<std::pair<double, double>> loadCurve;
  // Potentiostatic (surfaceRate k > 0): the x+ face's BC holds c_s = heldConcentration through
  // J = k (c_s - c) (a Robin condition, Bi = k L / D); `flux` is then unused and the analytic
  // solution is the plane wall's series (robinSlabAnalytic).
  double surfaceRate = 0, heldConcentration = 0.5;
  // Optional second flux BC on the x- face, constant (balance tests; 0: none).
  double fluxAtZero = 0;
  // OpenMP threads for the run (0: the OpenMP default). These problems have at most a few
  // hundred particles, for which one thread is fastest on a shared machine.
  int threads = 0;
  // Mechanics (irrelevant): wave speed sqrt((K + 4G/3)/rho) ~ 1.3e-3 L/time unit.
  double density = 1e6, bulkModulus = 1, shearModulus = 0.5;

  double endTime() const { return fourier * length * length / diffusivity; }
};

struct FluxSlabResult : RunSummary {
  double dt = 0;  // the (constant) step size
  // Against the analytic c at the particles at the end:
  double l2Error = 0;                  // sqrt(sum (c_p - c(x_p))^2 / sum c(x_p)^2)
  double maxError = 0;                 // max |c_p - c(x_p)| / max c(x_p)
  double interiorMaxError = 0;         // the same over the particles with x_p <= L/2 only
  double maxConcentration = 0;         // max c_p at the end
  double minConcentration = 0;         // min c_p over the run (undershoot below 0)
  double maxRestrictionDeviation = 0;  // max over the run of 1 - R(c_p) on flagged particles
  size_t fluxParticles = 0;            // particles the BC flags
  // Lithium balance: sum m c at the start and end, and sum over steps of
  // dt sum_p m_p p.externalScalarFlux (the rate of the step's start).
  double lithium0 = 0, lithium = 0, injected = 0;
  double balanceError() const;  // |lithium - lithium0 - injected| / |injected|
  // The same for the exact total, J t A_face (constant flux only), relative.
  double injectedVsExact = 0;
  double maxErrorAt = 0;  // x of the particle with the largest |c_p - c(x_p)|
  // The final profile: particle x, c_p and the analytic c(x_p), in particle order.
  std::vector<double> x, c, exact;
};

// Carslaw & Jaeger's solution above (x from the insulated face).
double fluxSlabAnalytic(double x, double t, double J, double L, double D);

// The same slab held at c_s through D dc/dx = k (c_s - c) at x = L (Carslaw & Jaeger §3.11; the
// plane wall with convection): c = c_s (1 - sum_n C_n exp(-z_n^2 D t / L^2) cos(z_n x / L)),
// z_n tan z_n = Bi = k L / D, C_n = 4 sin z_n / (2 z_n + sin 2 z_n).
double robinSlabAnalytic(double x, double t, double cs, double k, double L, double D);

// The .ups text of one case.
std::string fluxSlabInput(const FluxSlabCase& c);
// Builds the Simulation in memory, runs it to endTime (end_at_max_time_exactly) and measures.
FluxSlabResult runFluxSlab(const FluxSlabCase& c);

std::vector<int> fluxSlabStudyCells();
std::vector<int> fluxSlabQuickCells();

}  // namespace anode
