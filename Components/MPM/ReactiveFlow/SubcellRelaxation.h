// The relaxation of what the grid does not see of the particles' concentration
// (<subcell_concentration_relaxation>, quasi-static runs; docs/diffusion.md, "Sub-cell
// relaxation"). Eq. 8 adds each particle the rate interpolated from the nodes, so its difference
// from the grid's field at its place, c_p - sum_i S_ip c_i (c_i of Eq. 5), is carried through the
// diffusion unchanged: nothing on the grid acts on it, and a particle below its neighbours keeps
// losing lithium at their rate. Over dt (a quasi-static step's diffusion, before its sub-steps)
// each node draws the particles it reaches towards its c_i:
//   c_p <- c_p + sum_i S_ip a_i (c_i - c_p),   a_i = min(1, 4 eps D_i dt / dx^2),
// D_i = sum S m D / m_i, dx the largest cell edge. The lithium is conserved exactly (sum_p m_p S_ip
// (c_i - c_p) = 0 at every node) and c_p stays between its own and the nodes' values (a convex
// combination: no new extremes). It also smooths the field the grid resolves, as a diffusivity of
// a_i dx^2 / 4 dt = eps D would with one particle per cell and axis (linear hats: the
// interpolated c_i exceed a particle's c by dx^2/4 lap c), 3/4 of that with two, less with
// more; a particle's difference from its neighbours fades at 4 eps D / dx^2.
#pragma once

#include <algorithm>
#include <vector>

#include "Components/MPM/Interpolator.h"

namespace anode {

// eps above: the largest diffusivity the relaxation adds to the grid's waves, as a share of D.
constexpr double kSubcellRelaxationShare = 0.01;

// 4 eps dt / dx^2, dx the largest edge of a cell: D_i times it is a_i before its cap at 1.
inline double subcellRelaxationPerDiffusivity(double dt, double largestCellEdge) {
  return 4 * kSubcellRelaxationShare * dt / (largestCellEdge * largestCellEdge);
}

// sum S m D of particles [0, n) on `nodes` nodes (this rank's part: complete it over ranks), in
// particle order on one thread so that the sums do not depend on the threads.
inline void scatterMassDiffusivity(const std::vector<double>& mass,
                                   const std::vector<double>& diffusivity,
                                   const InterpolationWeights& W, size_t nodes,
                                   std::vector<double>& nodeMassDiffusivity) {
  nodeMassDiffusivity.assign(nodes, 0.0);
  for (size_t i = 0; i < mass.size(); ++i) {
    const double mD = mass[i] * diffusivity[i];
    if (mD == 0) continue;
    const size_t b = W.offset[i];
    for (int e = 0; e < W.count[i]; ++e) nodeMassDiffusivity[W.node[b + e]] += W.weight[b + e] * mD;
  }
}

// c_p <- c_p + sum S a_i (c_i - c_p) for particles [0, n), c_i = sum S m c / m_i of the P2G of
// these particles (nodeMassConcentration, nodeMass); adds each particle's change to change[i].
// The sums S m c change with c: P2G them again after this.
inline void relaxSubcellDifferences(std::vector<double>& concentration,
                                    const InterpolationWeights& W,
                                    const std::vector<double>& nodeMassConcentration,
                                    const std::vector<double>& nodeMass,
                                    const std::vector<double>& nodeMassDiffusivity,
                                    double relaxationPerDiffusivity, std::vector<double>& change) {
  const long n = static_cast<long>(concentration.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const double c = concentration[i];
    double dc = 0;
    const size_t b = W.offset[i];
    for (int e = 0; e < W.count[i]; ++e) {
      const int k = W.node[b + e];
      if (!(nodeMass[k] > 0)) continue;
      const double a =
          std::min(1.0, relaxationPerDiffusivity * nodeMassDiffusivity[k] / nodeMass[k]);
      dc += W.weight[b + e] * a * (nodeMassConcentration[k] / nodeMass[k] - c);
    }
    concentration[i] = c + dc;
    change[i] += dc;
  }
}

}  // namespace anode
