#include "Components/MPM/ActiveNodes.h"

#include <algorithm>
#include <limits>

namespace anode {

NodeRange nodesTouched(const InterpolationWeights& W, long first, long last) {
  long low = std::numeric_limits<long>::max(), high = -1;
  for (long i = first; i < last; ++i) {
    const size_t b = W.offset[i];
    for (int e = 0; e < W.count[i]; ++e) {
      low = std::min<long>(low, W.node[b + e]);
      high = std::max<long>(high, W.node[b + e]);
    }
  }
  return high < 0 ? NodeRange{} : NodeRange{low, high + 1};
}

ActiveNodes ActiveNodes::of(const Grid& g, const NodeBox& box) {
  ActiveNodes a;
  a.box = box.intersection(NodeBox{g.firstNode(), g.lastNode()});
  if (a.box.empty()) return a;
  const Vec3i& lo = a.box.first;
  const Vec3i& hi = a.box.last;
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j) {
      const long begin = g.nodeIndex(lo.x(), j, k), end = g.nodeIndex(hi.x(), j, k) + 1;
      if (!a.rows.empty() && a.rows.back().end == begin)
        a.rows.back().end = end;
      else
        a.rows.push_back({begin, end});
    }
  return a;
}

std::vector<NodeRange> ActiveNodes::within(const NodeRange& r) const {
  std::vector<NodeRange> cut;
  for (const NodeRange& row : rows) {
    const NodeRange c{std::max(row.begin, r.begin), std::min(row.end, r.end)};
    if (c.begin < c.end) cut.push_back(c);
  }
  return cut;
}

}  // namespace anode
