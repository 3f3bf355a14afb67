// G2P's sums for one particle over the node quads G2P reads (NodeQuads.h; filled by
// fillGatherQuads, ParticleLoops.h): shared by the explicit G2P (updateParticles, ParticleLoops.h)
// and the G2P of the concentration alone in a quasi-static step's diffusion
// (ReactiveFlow/ConcentrationSubstep.h), which uses their kernel lane.
#pragma once

#include "Components/MPM/Interpolator.h"
#include "Components/MPM/NodeQuads.h"

namespace anode {

// The sums of [v*, s] and [a, s-rate] times S and of [v*, s] times grad S over the nodes a
// particle touches (Eq. 8 and L = sum v* grad S; s the kernel's nodal value, c* with diffusion).
struct GatheredQuads {
  Quad velocity = Quad(0.0), acceleration = Quad(0.0);
  Quad byX = Quad(0.0), byY = Quad(0.0), byZ = Quad(0.0);

  // The kernel lane's sums.
  GatheredKernelValue kernelValue() const {
    const int cl = kKernelLane;
    return {Vec3(byX[cl], byY[cl], byZ[cl]), acceleration[cl], velocity[cl]};
  }
};

// Particle i's sums over quads (kGatherQuads per node), and the kernel's gather() per node into
// `particle`. Always inlined: it is the inner loop of G2P (GCC keeps it a call otherwise, about
// 1.4% more instructions on an explicit run).
template <class Kernel>
[[gnu::always_inline]] inline GatheredQuads gatherFromNodes(const InterpolationWeights& W, long i,
                                                            const NodeQuad* quads,
                                                            const Kernel& kernel,
                                                            typename Kernel::Particle& particle) {
  GatheredQuads s;
  const size_t b = W.offset[i];
  for (int e = 0; e < W.count[i]; ++e) {
    const int k = W.node[b + e];
    const double w = W.weight[b + e];
    const Vec3& grad = W.gradient[b + e];
    const NodeQuad* node = quads + kGatherQuads * static_cast<size_t>(k);
    const Quad v = load(node[0]);
    s.velocity += v * w;
    s.acceleration += load(node[1]) * w;
    s.byX += v * grad[0];
    s.byY += v * grad[1];
    s.byZ += v * grad[2];
    kernel.gather(particle, k, w);
  }
  return s;
}

}  // namespace anode
