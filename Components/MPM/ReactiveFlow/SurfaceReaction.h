// The surface reaction of a galvanostatic <scalar_flux> with <surface_reaction> (ours; DESIGN.md
// §9; docs/diffusion.md, "Surface reaction and the electrode's potential"). Butler-Volmer: the
// lithium flux into a flagged particle per unit area (normalised c times length per time, the
// unit of a <scalar_flux> load) is
//   j = J0 [exp(-alpha f eta) - exp((1 - alpha) f eta)],   eta = phi - U(c),   f = F / RT,
// positive (lithiation) where the electrode's potential phi is below the particle's open-circuit
// potential, of the ideal free energy of mixing with the chemical potential's stress term
// (ChemicalPotential.h):
//   U(c) = U0 - (1 / f) ln(c / (1 - c)) + (1 / f) phi_s,   phi_s = k tau_h,
// c normalised, phi_s 0 unless the material's flux has a stress part (so a tensile surface
// raises U: lithium enters it more readily). The BC's current fixes phi, one potential for its
// whole surface: sum_p w_p j(phi - U_p) = Q, w_p = m_p A_p / V_p c_max, solved by Newton's
// method kept inside a bracket.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "Core/Parallel/Communicator.h"

namespace anode {

struct SurfaceReaction {
  double temperature = 0;            // <temperature>, K
  double openCircuitPotential = 0;   // <open_circuit_potential> U0, V
  double exchangeFlux = 0;           // <exchange_flux> J0 = i0 / (F c_max,molar), the load's unit
  double transferCoefficient = 0.5;  // <transfer_coefficient> alpha, in (0, 1)
  // <lower_cutoff_potential>, <upper_cutoff_potential> (V): a charge (lithiation) ends where phi
  // falls to the lower, a discharge where it rises to the upper, until the load curve's next
  // segment.
  double lowerCutoff = -std::numeric_limits<double>::infinity();
  double upperCutoff = std::numeric_limits<double>::infinity();

  // RT / F = k_B T / e, V.
  double thermalVoltage() const { return 8.617333262e-5 * temperature; }
  // U of a particle at normalised c in (0, 1) with the stress's part phi_s of mu / RT.
  double openCircuit(double c, double stressPotential) const {
    return openCircuitPotential + thermalVoltage() * (stressPotential - std::log(c / (1 - c)));
  }
  // j at potential phi of a particle whose open-circuit potential is U.
  double flux(double phi, double U) const {
    const double x = (phi - U) / thermalVoltage();
    return exchangeFlux *
           (std::exp(-transferCoefficient * x) - std::exp((1 - transferCoefficient) * x));
  }
  // dj/dphi (< 0): -(J0 / (RT/F)) [alpha exp(-alpha x) + (1 - alpha) exp((1 - alpha) x)],
  // x = (phi - U) / (RT/F).
  double fluxDerivative(double phi, double U) const {
    const double x = (phi - U) / thermalVoltage();
    return -exchangeFlux / thermalVoltage() *
           (transferCoefficient * std::exp(-transferCoefficient * x) +
            (1 - transferCoefficient) * std::exp((1 - transferCoefficient) * x));
  }
  // |dj/dc| through U at normalised c, |dj/dphi| (RT/F) / (c (1 - c)): how fast a particle's
  // flux answers its own c.
  double fluxSlope(double phi, double U, double c) const {
    return -fluxDerivative(phi, U) * thermalVoltage() / (c * (1 - c));
  }
};

// The potential at which sites of weights w_k (m A / V c_max) and open-circuit potentials U_k
// take up `rate` (sum w j = rate), over every rank when `overRanks` (their sites are theirs):
// bracketed between the extreme U_k, widened by doubling steps of RT / F, then Newton's steps
// from the bracket's middle, a bisection where a step would leave it, to round-off: the same
// phi from the same state, whatever came before. One reduction per iteration.
double potentialCarrying(Collective, const SurfaceReaction& r, const std::vector<double>& weight,
                         const std::vector<double>& openCircuit, double rate, bool overRanks);

}  // namespace anode
