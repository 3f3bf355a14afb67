// Shape functions (UINTAH_UPS.md §8.1): for one particle, the nodes it touches, the weights S_ip
// and their spatial gradients. Computed once per particle per step into InterpolationWeights and
// reused by every task of the step.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "Core/Grid/Grid.h"
#include "Core/Math/Types.h"

namespace anode {

enum class InterpolatorKind { Linear, GIMP, CPDI };

// Most nodes one particle can touch: 8 (linear), 27 (GIMP), 64 (CPDI: 8 corners x 8 nodes).
int maxNodesPerParticle(InterpolatorKind kind);
std::string interpolatorName(InterpolatorKind kind);

// Fills nodes/weights/gradients for one particle and returns how many were written, or -1 when
// the particle's support reaches beyond the grid's nodes. `size` is the reference domain in cell
// units (columns are edge vectors) and F the deformation gradient at the start of the step.
int linearWeights(const Grid& g, const Vec3& x, int32_t* nodes, double* w, Vec3* grad);
int gimpWeights(const Grid& g, const Vec3& x, const Mat3& size, int32_t* nodes, double* w, Vec3* grad);
int cpdiWeights(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F, int32_t* nodes,
                double* w, Vec3* grad);

// Per-particle weights of one material for the current step, fixed stride per particle.
struct InterpolationWeights {
  int stride = 0;
  std::vector<uint8_t> count;
  std::vector<int32_t> node;
  std::vector<double> weight;
  std::vector<Vec3> gradient;

  void resize(size_t particles, int perParticle) {
    stride = perParticle;
    count.assign(particles, 0);
    node.resize(particles * perParticle);
    weight.resize(particles * perParticle);
    gradient.resize(particles * perParticle);
  }
};

}  // namespace anode
