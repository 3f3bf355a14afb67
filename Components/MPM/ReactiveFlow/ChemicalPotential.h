// The stress's part of lithium's chemical potential (<diffusion_model type="chemical_potential">,
// DESIGN.md §9; docs/diffusion.md, "Stress-driven diffusion"). With mu = RT ln(c/(1 - c)) -
// Omega tau_h (c normalised by max_concentration) the flux J = -(D c (1 - c) / RT) grad mu is
//   J = -D grad c + D c (1 - c) grad phi,   phi = Omega tau_h / RT = k tau_h,
// in units of the input's c: J = -D grad c + D c (1 - c / c_max) grad phi. tau_h = J_F tr(sigma)/3
// is the Kirchhoff mean stress (J_F = det F), the work-conjugate of the swelling's logarithmic
// volume strain 3 eta c: a reference volume's swelling by dc takes the work 3 eta tau_h dc, and
// Omega = 3 eta / c_max,molar per mole (k = 3 eta / (c_max,molar R T), <cmax_RT>).
//
// Within a quasi-static step the stress is that of the pass's particles (the step's start, or its
// predicted end), which the pass's c does not change. Taken so alone, the coupling is explicit in
// the stress: swelling makes the mean stress fall where c rises, by 12 K G / (3K + 4G) eta dc in
// any linear elastic body (Beltrami-Michell: sigma_kk + 2 E eta c / (1 - nu) is harmonic), and
// tau_h by J times that, so the stress's flux acts as a diffusivity D s_p c (1 - c),
// s_p = k eta 12 K G / (3K + 4G) J_p, that an explicit coupling takes with steps below
// dx^2 / (2 D s_p c (1 - c)). A pass takes that local part implicitly: phi(c) = phi_0 - s_p (c -
// c_0), c_0 the c the pass's stress holds, so
//   J = -D (1 + s_p c (1 - c)) grad c + D c (1 - c) (grad phi_0 + s_p grad c_0),
// the first term a diffusivity the pass's integrator bounds its steps by (Eq. 44, RKL2's stages),
// the second frozen over the pass; what s_p leaves out of the stress's response (the harmonic
// part, plastic flow) stays explicit. Both are exact as dt -> 0 (c -> c_0). The trapezoidal mean
// of a pass on the step's start and one on its predicted end (c_0 the first pass's end there)
// makes the linearization's error in phi, (s_p - s_true)(c - c_0), change sign over the step.
// grad phi_0 and grad c_0 come from the nodes (mass-weighted P2G, as c's, Eq. 5) by the weights'
// gradients, once per diffusion pass.
#pragma once

#include <vector>

#include "Components/MPM/Interpolator.h"
#include "Core/Math/Types.h"

namespace anode {

// phi = k tau_h of a particle: `perStress` k (1 / the input's stress unit), Cauchy `stress`,
// deformation gradient F.
inline double stressPotential(double perStress, const Mat3& stress, const Mat3& F) {
  return perStress * F.determinant() * stress.trace() / 3.0;
}

// The fall of the mean stress per unit c where a linear elastic body swells by eta c on each
// axis: 12 K G / (3K + 4G) eta (= 2 E eta / (3 (1 - nu))).
inline double localSwellingPressure(double eta, double K, double G) {
  return 12 * K * G / (3 * K + 4 * G) * eta;
}

// The pass's diffusivity of grad c: D (1 + s_p c (1 - c)), c normalised, s_p = `stabilization` J.
inline double effectiveDiffusivity(double D, double stabilization, double J, double c) {
  return D * (1 + stabilization * J * c * (1 - c));
}

// sum S m phi and sum S m c_0 of particles [0, n) on `nodes` nodes (this rank's part: complete
// them over ranks), c_0 = (c + c0Change) / cmax the normalised c their stress holds, in particle
// order on one thread so that the sums do not depend on the threads.
inline void scatterStressPotential(double perStress, double cmax, const std::vector<double>& mass,
                                   const std::vector<Mat3>& stress, const std::vector<Mat3>& F,
                                   const std::vector<double>& concentration,
                                   const std::vector<double>* c0Change,
                                   const InterpolationWeights& W, size_t nodes,
                                   std::vector<double>& nodeMassPotential,
                                   std::vector<double>& nodeMassConcentration) {
  nodeMassPotential.assign(nodes, 0.0);
  nodeMassConcentration.assign(nodes, 0.0);
  for (size_t i = 0; i < mass.size(); ++i) {
    const double mPhi = mass[i] * stressPotential(perStress, stress[i], F[i]);
    const double mC0 = mass[i] * (concentration[i] + (c0Change ? (*c0Change)[i] : 0.0)) / cmax;
    const size_t b = W.offset[i];
    for (int e = 0; e < W.count[i]; ++e) {
      nodeMassPotential[W.node[b + e]] += W.weight[b + e] * mPhi;
      nodeMassConcentration[W.node[b + e]] += W.weight[b + e] * mC0;
    }
  }
}

// grad phi_0 + s_p grad c_0 of particles [0, n), s_p = `stabilization` det F_p, from the nodes'
// sums and masses: sum (phi_k + s_p c_k) grad S_k with phi_k = (S m phi)_k / m_k and c_k = (S m
// c_0)_k / m_k (nothing from a node without mass).
inline void gatherStressPotentialGradient(const InterpolationWeights& W,
                                          const std::vector<double>& nodeMassPotential,
                                          const std::vector<double>& nodeMassConcentration,
                                          const std::vector<double>& nodeMass, double stabilization,
                                          const std::vector<Mat3>& F, std::vector<Vec3>& gradient) {
  const long n = static_cast<long>(gradient.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const double s = stabilization * F[i].determinant();
    Vec3 g = Vec3::Zero();
    for (size_t e = W.offset[i]; e < W.offset[i] + W.count[i]; ++e) {
      const int k = W.node[e];
      if (nodeMass[k] > 0)
        g += (nodeMassPotential[k] + s * nodeMassConcentration[k]) / nodeMass[k] * W.gradient[e];
    }
    gradient[i] = g;
  }
}

}  // namespace anode
