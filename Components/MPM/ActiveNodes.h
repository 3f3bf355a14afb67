// The nodes a step's grid tasks visit: the box of stored nodes the particles' weights reach (in a
// distributed run, every rank's particles), as rows of contiguous flat indices, so that a small
// body in a large grid costs its own nodes and not whole layers of the grid. Outside them the
// nodal fields are zero, except the values face boundary conditions set.
#pragma once

#include <omp.h>

#include <algorithm>
#include <vector>

#include "Components/MPM/GhostNodes.h"
#include "Components/MPM/Interpolator.h"
#include "Core/Grid/Grid.h"

namespace anode {

// A range of flat node indices [begin, end).
struct NodeRange {
  long begin = 0, end = 0;
  bool contains(long k) const { return begin <= k && k < end; }
};

// The nodes the weights of particles [first, last) touch (empty when they touch none).
NodeRange nodesTouched(const InterpolationWeights& W, long first, long last);

// The smallest box holding both (either may be empty).
inline NodeBox hullOf(const NodeBox& a, const NodeBox& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {a.first.cwiseMin(b.first), a.last.cwiseMax(b.last)};
}
#pragma omp declare reduction(hull:NodeBox                         \
                              : omp_out = hullOf(omp_out, omp_in)) \
    initializer(omp_priv = NodeBox{})

struct ActiveNodes {
  NodeBox box;                  // grid indices
  std::vector<NodeRange> rows;  // x rows of the box; rows meeting end to end are merged

  // The rows of `box` on the nodes g stores (the box is clipped to them).
  static ActiveNodes of(const Grid& g, const NodeBox& box);
  // The rows cut to the flat range r (rows outside it left out).
  std::vector<NodeRange> within(const NodeRange& r) const;
};

// Calls f(begin, end) for thread t of `threads` on the pieces of `rows` that make its share of
// their nodes: the t-th of equal consecutive parts of them, whatever the rows' lengths.
template <class F>
void forEachRangeOfThread(const std::vector<NodeRange>& rows, int t, int threads, F&& f) {
  long total = 0;
  for (const NodeRange& r : rows) total += r.end - r.begin;
  long skip = total * t / threads, take = total * (t + 1) / threads - skip;
  for (const NodeRange& r : rows) {
    if (take == 0) break;
    const long length = r.end - r.begin;
    if (skip >= length) {
      skip -= length;
      continue;
    }
    const long begin = r.begin + skip, end = std::min(r.end, begin + take);
    f(begin, end);
    take -= end - begin;
    skip = 0;
  }
}

// f(k) for each node k of a piece [begin, end).
template <class F>
auto nodeByNode(F& f) {
  return [&f](long begin, long end) {
    for (long k = begin; k < end; ++k) f(k);
  };
}

// Calls f(k) for thread t of `threads` on its share of the nodes of `rows` (as above).
template <class F>
void forEachNodeOfThread(const std::vector<NodeRange>& rows, int t, int threads, F&& f) {
  forEachRangeOfThread(rows, t, threads, nodeByNode(f));
}

// Calls f(begin, end) on pieces of `rows` covering each node once, shared among the threads:
// for work done on a range of nodes at once, such as clearing fields.
template <class F>
void forEachNodeRange(const std::vector<NodeRange>& rows, F&& f) {
#pragma omp parallel
  forEachRangeOfThread(rows, omp_get_thread_num(), omp_get_num_threads(), f);
}

// Calls f(k) for every node k of `rows`, shared among the threads.
template <class F>
void forEachNode(const std::vector<NodeRange>& rows, F&& f) {
  forEachNodeRange(rows, nodeByNode(f));
}

}  // namespace anode
