// Shape functions (UINTAH_UPS.md §8.1): for one particle, the nodes it touches, the weights S_ip
// and their spatial gradients. Computed once per particle per step into InterpolationWeights and
// reused by every task of the step.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "Components/MPM/CpdiCorners.h"
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
int gimpWeights(const Grid& g, const Vec3& x, const Mat3& size, int32_t* nodes, double* w,
                Vec3* grad);
int cpdiWeights(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F, int32_t* nodes,
                double* w, Vec3* grad);
// The same in two parts: the domain's corners (of one particle, or of Pack::size() particles at
// once from x[0], size[0], F[0] on: the same numbers), then the weights from them.
void cpdiCorners(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F, CpdiCorners& out);
void cpdiCornersOfPack(const Grid& g, const Vec3* x, const Mat3* size, const Mat3* F,
                       CpdiCorners* out);
int cpdiWeights(const Grid& g, const CpdiCorners& corners, int32_t* nodes, double* w, Vec3* grad);
// cpdiWeights may write entries beyond the count it returns, never beyond cpdiCapacity's.
// The most entries cpdiWeights can write for this particle (the nodes of the cells its corners
// span, at most 64): a domain within one cell per axis touches 27 nodes, not 64.
int cpdiCapacity(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F);

// Bounds on the nodes a particle's weights can touch: within [first, last] (grid indices), for
// ranks that send only the shared nodes their particles reach.
void supportBounds(InterpolatorKind kind, const Grid& g, const Vec3& x, const Mat3& size,
                   const Mat3& F, Vec3i& first, Vec3i& last);

// Per-particle weights of one material for the current step: particle i owns the entries
// [offset[i], offset[i] + count[i]).
struct InterpolationWeights {
  std::vector<uint8_t> count;
  std::vector<size_t> offset;
  std::vector<int32_t> node;
  std::vector<double> weight;
  std::vector<Vec3> gradient;

  // Lays out `capacity[i]` entries for each particle; storage only grows between releases.
  void layOut(const std::vector<uint8_t>& capacity) {
    offset.resize(capacity.size());
    count.resize(capacity.size());
    size_t total = 0;
    for (size_t i = 0; i < capacity.size(); ++i) {
      offset[i] = total;
      total += capacity[i];
    }
    if (total > node.size()) {
      // Freed before growing (the old entries are not needed; resizing would hold both), with
      // 1/16 to spare so that domains stretching step by step do not reallocate every step.
      node = {}, weight = {}, gradient = {};
      const size_t grown = total + total / 16;
      node.resize(grown);
      weight.resize(grown);
      gradient.resize(grown);
    }
  }
};

}  // namespace anode
