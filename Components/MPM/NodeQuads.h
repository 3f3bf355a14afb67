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
// gradient: the mechanics' [mass (Eq. 4), momentum] first and [internal force, kernel lane] last.
// A subcomponent's kernel asks for the quads between (its scatterWeightQuads, counting the
// mechanics' first) and may use the kernel lane; it names their lanes itself (ReactiveFlow's
// ConcentrationKernels.h). The particle loops are compiled per kernel, so the layout is fixed
// at compile time.
template <int WeightQuads>
struct ScatterTerms {
  static constexpr int quads = WeightQuads + 1;
  // quad s += byWeight[s] S (s < WeightQuads); the last quad -= sum_d byGradient[d] dS/dx_d.
  alignas(32) double byWeight[WeightQuads][4] = {};
  alignas(32) double byGradient[3][4] = {};
};
namespace ScatterLane {  // the mechanics' lanes of the first and the last quad above
constexpr int mass = 0, momentum = 1;
constexpr int internalForce = 0;
}  // namespace ScatterLane

// P2G of a kernel's sums alone (scatterConcentrationToNodes): its last quad of weighted terms
// and the quad of gradient terms, whose kernel lane it uses.
constexpr int kConcentrationScatterQuads = 2;

// The lane the mechanics leaves to a subcomponent's kernel: of P2G's last quad, and of both of
// G2P's quads, where it holds the kernel's nodal value and rate (nodeValues).
constexpr int kKernelLane = 3;

// What G2P reads at a node k, quads 2k and 2k + 1: [velocity_star, s] [acceleration, s-rate], s
// the kernel's nodal value (zero without one). Its velocity and acceleration are sums over
// nodes of the quads times S, L and grad s the first quad times grad S.
constexpr int kGatherQuads = 2;

// What G2P sums for a particle from the kernel's nodal value s and its rate.
struct GatheredKernelValue {
  Vec3 gradient;  // sum s grad S
  double rate;    // sum S s-rate
  double value;   // sum S s
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
