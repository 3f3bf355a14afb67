// The step's task 1: each particle's interpolation weights S_ip and gradients grad S_ip
// (UINTAH_UPS.md §8.1), computed once per step for every later task, and the nodes the step's
// grid tasks visit.
#include <omp.h>

#include <algorithm>

#include "Components/MPM/CpdiCorners.h"
#include "Components/MPM/MPM.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

void MPM::computeWeightsAndActiveNodes(Collective every) {
  NodeBox reached;
  collective::stopTogether(every, [&] { reached = computeInterpolationWeights(); });
  // The ghost nodes get the other ranks' parts: a stored node takes part in the step where any
  // rank's particles reach it (outside the ranks' stopTogether, as it is collective).
  previous_ = step_.active.box;
  NodeBox all = layout_.distributed() ? layout_.ghosts()->setReach(every, reached) : reached;
  // An implicit run shares its owned unknowns' corrections (Implicit/EquilibriumSolver.h) on
  // shared nodes its own particles may not reach: its reach is its window within all of theirs.
  if (layout_.distributed() && problem_.flags.implicit)
    all = layout_.ghosts()->setReach(
        every, NodeBox{grid().firstNode(), grid().lastNode()}.intersection(all));
  step_.active = ActiveNodes::of(grid(), all);
}

NodeBox MPM::computeInterpolationWeights() {
  NodeBox reached;
  for (size_t m = 0; m < materials_.size(); ++m) {
    const ParticleSet& p = materials_[m].particles;
    InterpolationWeights& W = step_.weights[m];
    const long n = static_cast<long>(p.count());
    std::vector<uint8_t>& capacity = capacity_[m];
    capacity.resize(n);
    if (problem_.flags.interpolator == InterpolatorKind::CPDI) {
#pragma omp parallel for schedule(static)
      for (long i = 0; i < n; ++i)
        capacity[i] = static_cast<uint8_t>(cpdiCapacity(grid(), p.x[i], p.size[i], p.F[i]));
    } else {
      std::fill(capacity.begin(), capacity.end(),
                static_cast<uint8_t>(maxNodesPerParticle(problem_.flags.interpolator)));
    }
    W.layOut(capacity);
    long firstOutside = n;
    // Particle i's weights, `count` entries (-1: beyond the nodes stored here), are in place;
    // `support` bounds the nodes they touch.
    const auto record = [&W](long i, int count, const NodeBox& support, long& outside,
                             NodeBox& box) {
      if (count < 0) outside = std::min(outside, i);
      W.count[i] = static_cast<uint8_t>(std::max(count, 0));
      if (count > 0) box = hullOf(box, support);
    };
    if (problem_.flags.interpolator == InterpolatorKind::CPDI) {
      // The corners of a pack of particles at once, then each one's weights from its corners.
      constexpr long lanes = static_cast<long>(Pack::size());
#pragma omp parallel for schedule(static) reduction(min : firstOutside) reduction(hull : reached)
      for (long first = 0; first < n; first += lanes) {
        CpdiCorners corners[lanes];
        const long last = std::min(n, first + lanes);
        if (last - first == lanes)
          cpdiCornersOfPack(grid(), &p.x[first], &p.size[first], &p.F[first], corners);
        else
          for (long i = first; i < last; ++i)
            cpdiCorners(grid(), p.x[i], p.size[i], p.F[i], corners[i - first]);
        for (long i = first; i < last; ++i) {
          const CpdiCorners& c = corners[i - first];
          const size_t b = W.offset[i];
          record(i, cpdiWeights(grid(), c, &W.node[b], &W.weight[b], &W.gradient[b]),
                 NodeBox{Vec3i(c.lowest[0], c.lowest[1], c.lowest[2]),
                         Vec3i(c.highest[0], c.highest[1], c.highest[2])},
                 firstOutside, reached);
        }
      }
    } else {
#pragma omp parallel for schedule(static) reduction(min : firstOutside) reduction(hull : reached)
      for (long i = 0; i < n; ++i) {
        const size_t b = W.offset[i];
        NodeBox support;
        supportBounds(problem_.flags.interpolator, grid(), p.x[i], p.size[i], p.F[i], support.first,
                      support.last);
        record(i, computeWeights(grid(), p, i, &W.node[b], &W.weight[b], &W.gradient[b]), support,
               firstOutside, reached);
      }
    }
    if (firstOutside < n) throwOutsideWindow(m, firstOutside);
  }
  return reached;
}

void MPM::throwOutsideWindow(size_t m, long i) const {
  const ParticleSet& p = materials_[m].particles;
  int32_t node[64];
  double weight[64];
  Vec3 gradient[64];
  if (computeWeights(layout_.problemGrid(), p, i, node, weight, gradient) < 0)
    throw SimulationError(
        describeParticle(materials_[m], m, i) +
        " has left the grid (its interpolation support reaches beyond the last node)");
  throw SimulationError(describeParticle(materials_[m], m, i) + " on rank " +
                        std::to_string(Communicator::rank()) +
                        ": its CPDI domain reaches beyond the rank's ghost layer (" +
                        std::to_string(layout_.ghostWidth()) +
                        " cells): it stretched further than when the ranks' boxes were drawn "
                        "(<refine_particles> splits stretched particles)");
}

int MPM::computeWeights(const Grid& g, const ParticleSet& p, long i, int32_t* node, double* w,
                        Vec3* grad) const {
  switch (problem_.flags.interpolator) {
    case InterpolatorKind::Linear:
      return linearWeights(g, p.x[i], node, w, grad);
    case InterpolatorKind::GIMP:
      return gimpWeights(g, p.x[i], p.size[i], node, w, grad);
    case InterpolatorKind::CPDI:
      return cpdiWeights(g, p.x[i], p.size[i], p.F[i], node, w, grad);
  }
  return -1;
}

}  // namespace anode
