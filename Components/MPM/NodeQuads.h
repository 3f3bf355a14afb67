// The nodal values one particle loop reads or adds at a node, side by side in quads of four
// doubles, so that a particle's gather from a node or scatter to it is a few vector operations
// instead of a dozen scalar ones on as many arrays (docs/performance.md, "Nodes as quads").
// P2G's quads are spread into the grid's fields just after it, G2P's are filled from them just
// before it (in the same memory): the grid's fields keep their one meaning for the whole step.
#pragma once

#include "Core/Math/Simd.h"

namespace anode {

struct alignas(32) NodeQuad {
  double value[4];
};

inline Quad load(const NodeQuad& q) {
  return Quad(q.value, stdx::vector_aligned);
}
inline void store(const Quad& v, NodeQuad& q) {
  v.copy_to(q.value, stdx::vector_aligned);
}

// What P2G adds at a node, in `WeightQuads` quads multiplied by the weight S and one by its
// gradient. Without diffusion (1 + 1 quads): [mass (Eq. 4), momentum] [internal force, 0]. With
// diffusion (2 + 1): [mass, momentum] [m c (Eq. 5), flux source G (Eq. 18), receiver weights
// W_in, W_out (docs/diffusion.md, step 5)] [internal force, diffusion rate R (Eq. 7)].
template <int WeightQuads>
struct ScatterTerms {
  static constexpr int quads = WeightQuads + 1;
  // quad s += byWeight[s] S (s < WeightQuads); the last quad -= sum_d byGradient[d] dS/dx_d.
  alignas(32) double byWeight[WeightQuads][4] = {};
  alignas(32) double byGradient[3][4] = {};
};
namespace ScatterLane {  // lanes of the quads above
constexpr int mass = 0, momentum = 1;
constexpr int massConcentration = 0, fluxSource = 1, receiverWeightIn = 2, receiverWeightOut = 3;
constexpr int internalForce = 0, diffusionRate = 3;
}  // namespace ScatterLane

// What G2P reads at a node k, quads 2k and 2k + 1: [velocity_star, c*] [acceleration, the nodal
// concentration rate] (c* and the rate zero without diffusion). Its velocity and acceleration
// are sums over nodes of the quads times S, L and grad c the first quad times grad S.
constexpr int kGatherQuads = 2, kConcentrationLane = 3;

// What G2P sums for a particle from c* and the concentration rate.
struct GatheredConcentration {
  Vec3 gradient;  // sum c* grad S
  double rate;    // sum S c-rate
  double value;   // sum S c*
};

// Zeroes `count` quads.
inline void clearQuads(NodeQuad* q, int count) {
  for (int s = 0; s < count; ++s) store(Quad(0.0), q[s]);
}

// sum += added, `count` quads, lane by lane.
inline void addQuads(NodeQuad* sum, const NodeQuad* added, int count) {
  for (int s = 0; s < count; ++s) store(load(sum[s]) + load(added[s]), sum[s]);
}

}  // namespace anode
