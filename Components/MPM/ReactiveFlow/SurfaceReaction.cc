#include "Components/MPM/ReactiveFlow/SurfaceReaction.h"

#include <algorithm>

namespace anode {

double potentialCarrying(Collective every, const SurfaceReaction& r,
                         const std::vector<double>& weight, const std::vector<double>& openCircuit,
                         double rate, bool overRanks) {
  // The sites' current less `rate` at phi, and its slope (it falls as phi rises).
  const auto excess = [&](double phi, double& slope) {
    double sums[2] = {0, 0};
    for (size_t k = 0; k < weight.size(); ++k) {
      sums[0] += weight[k] * r.flux(phi, openCircuit[k]);
      sums[1] += weight[k] * r.fluxDerivative(phi, openCircuit[k]);
    }
    if (overRanks) collective::sum(every, sums, 2);
    slope = sums[1];
    return sums[0] - rate;
  };
  double bounds[2] = {std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};  // min U, -max U
  for (double U : openCircuit)
    bounds[0] = std::min(bounds[0], U), bounds[1] = std::min(bounds[1], -U);
  if (overRanks) collective::minimum(every, bounds, 2);
  double lo = bounds[0], hi = -bounds[1], slope = 0;
  for (double step = r.thermalVoltage(); excess(lo, slope) < 0; step *= 2) lo -= step;
  for (double step = r.thermalVoltage(); excess(hi, slope) > 0; step *= 2) hi += step;
  double phi = 0.5 * (lo + hi);
  for (int k = 0; k < 200; ++k) {
    const double value = excess(phi, slope);
    if (value == 0) break;
    (value > 0 ? lo : hi) = phi;
    double next = phi - value / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool converged = std::abs(next - phi) <= 1e-15 * (1 + std::abs(phi));
    phi = next;
    if (converged || hi - lo <= 1e-15 * (1 + std::abs(phi))) break;
  }
  return phi;
}

}  // namespace anode
