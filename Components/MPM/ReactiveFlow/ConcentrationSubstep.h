// G2P of the concentration alone, for the diffusion sub-steps of a quasi-static step
// (docs/quasi-static.md): the particles stay where the step began, so each sub-step is P2G, the
// grid's concentration equations and this gather, with the diffusion kernel of an explicit step
// (ReactiveFlow's ConcentrationGather) and the same node quads and per-particle sums as its G2P
// (NodeGather.h), the kernel lane of which it uses.
#pragma once

#include <vector>

#include "Components/MPM/Interpolator.h"
#include "Components/MPM/NodeGather.h"
#include "Components/MPM/NodeQuads.h"
#include "Components/MPM/ParticleSet.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"

namespace anode {

// Updates the concentration of particles [0, n) over dt and adds each one's change to dc[i].
template <class Kernel>
void updateConcentrationOnly(const ParticleSet& p, const InterpolationWeights& W,
                             const NodeQuad* quads, const Kernel& kernel, double dt,
                             std::vector<double>& dc) {
  const long n = static_cast<long>(p.count());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    typename Kernel::Particle a{};
    const GatheredQuads sums = gatherFromNodes(W, i, quads, kernel, a);
    dc[i] += kernel.update(i, a, sums.kernelValue(), dt);
  }
}

// grad c of particles [0, n) from the nodal c: sum c_k grad S_k (the gradient a sub-step's G2P
// leaves, of the nodal c instead of c*).
inline void gatherConcentrationGradient(ParticleSet& p, const InterpolationWeights& W,
                                        const std::vector<double>& nodal) {
  DiffusionParticles d = diffusionParticles(p);
  const long n = static_cast<long>(p.count());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    Vec3 gradient = Vec3::Zero();
    for (size_t e = W.offset[i]; e < W.offset[i] + W.count[i]; ++e)
      gradient += nodal[W.node[e]] * W.gradient[e];
    d.concentrationGradient[i] = gradient;
  }
}

}  // namespace anode
