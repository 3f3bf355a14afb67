// Pins the nodes the grid tasks visit (Components/MPM/ActiveNodes.h): a box of grid nodes as rows
// of flat indices, clipped to the stored nodes, and each node given to exactly one thread; and
// the flat range a block of particles' weights touch (P2G's thread buffers).
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <vector>

#include "Components/MPM/ActiveNodes.h"

namespace anode {
namespace {

Grid testGrid() {
  Grid g;
  g.lower = Vec3::Zero();
  g.upper = Vec3(1.0, 1.0, 1.0);
  g.cells = Vec3i(9, 7, 5);  // nodes 10 x 8 x 6
  g.dx = g.upper.cwiseQuotient(g.cells.cast<double>());
  return g;
}

std::vector<long> nodesOf(const std::vector<NodeRange>& rows) {
  std::vector<long> nodes;
  for (const NodeRange& r : rows)
    for (long k = r.begin; k < r.end; ++k) nodes.push_back(k);
  return nodes;
}

TEST(ActiveNodes, NodesTouchedSpanTheParticlesWeights) {
  InterpolationWeights W;
  W.layOut({2, 3, 2});
  const int32_t nodes[] = {40, 12, 7, 90, 33, 5, 6};
  std::copy(std::begin(nodes), std::end(nodes), W.node.begin());
  W.count = {2, 3, 0};  // the third particle's entries are laid out but not written
  const NodeRange all = nodesTouched(W, 0, 3), second = nodesTouched(W, 1, 2);
  EXPECT_EQ(all.begin, 7);
  EXPECT_EQ(all.end, 91);
  EXPECT_EQ(second.begin, 7);
  EXPECT_EQ(second.end, 91);
  EXPECT_EQ(nodesTouched(W, 0, 1).begin, 12);
  EXPECT_EQ(nodesTouched(W, 0, 1).end, 41);
  const NodeRange none = nodesTouched(W, 2, 3);
  EXPECT_EQ(none.begin, none.end);
  EXPECT_TRUE(all.contains(7) && all.contains(90));
  EXPECT_FALSE(all.contains(6) || all.contains(91));
}

TEST(ActiveNodes, RowsHoldExactlyTheBoxNodes) {
  const Grid g = testGrid();
  const NodeBox box{Vec3i(2, 1, 3), Vec3i(4, 5, 4)};
  const ActiveNodes a = ActiveNodes::of(g, box);
  EXPECT_EQ(a.rows.size(), 5u * 2u);  // one row of x per (j, k)
  std::vector<long> expected;
  for (int k = 3; k <= 4; ++k)
    for (int j = 1; j <= 5; ++j)
      for (int i = 2; i <= 4; ++i) expected.push_back(g.nodeIndex(i, j, k));
  EXPECT_EQ(nodesOf(a.rows), expected);
}

TEST(ActiveNodes, WholeRowsMergeAndTheBoxIsClippedToTheGrid) {
  const Grid g = testGrid();
  const ActiveNodes a = ActiveNodes::of(g, NodeBox{Vec3i(-3, 2, 1), Vec3i(20, 3, 2)});
  EXPECT_EQ(a.box.first, Vec3i(0, 2, 1));
  EXPECT_EQ(a.box.last, Vec3i(9, 3, 2));
  ASSERT_EQ(a.rows.size(), 2u);  // rows j = 2, 3 meet end to end in each of k = 1, 2
  EXPECT_EQ(a.rows[0].begin, g.nodeIndex(0, 2, 1));
  EXPECT_EQ(a.rows[0].end, g.nodeIndex(9, 3, 1) + 1);
  EXPECT_TRUE(ActiveNodes::of(g, NodeBox{}).rows.empty());
}

TEST(ActiveNodes, WithinCutsTheRowsToARange) {
  const Grid g = testGrid();
  const ActiveNodes a = ActiveNodes::of(g, NodeBox{Vec3i(2, 1, 3), Vec3i(4, 5, 4)});
  const NodeRange r{g.nodeIndex(3, 2, 3), g.nodeIndex(3, 4, 3)};
  std::vector<long> expected;
  for (long k : nodesOf(a.rows))
    if (r.contains(k)) expected.push_back(k);
  EXPECT_EQ(nodesOf(a.within(r)), expected);
  EXPECT_EQ(expected.front(), g.nodeIndex(3, 2, 3));
  EXPECT_TRUE(a.within(NodeRange{0, g.nodeIndex(0, 0, 3)}).empty());
}

TEST(ActiveNodes, HullHoldsBothBoxes) {
  const NodeBox a{Vec3i(1, 2, 3), Vec3i(4, 5, 6)}, b{Vec3i(0, 3, 5), Vec3i(2, 8, 6)};
  const NodeBox h = hullOf(a, b);
  EXPECT_EQ(h.first, Vec3i(0, 2, 3));
  EXPECT_EQ(h.last, Vec3i(4, 8, 6));
  EXPECT_EQ(hullOf(NodeBox{}, a).first, a.first);
  EXPECT_EQ(hullOf(a, NodeBox{}).last, a.last);
  EXPECT_TRUE(hullOf(NodeBox{}, NodeBox{}).empty());
}

TEST(ActiveNodes, EveryNodeGoesToExactlyOneThread) {
  const Grid g = testGrid();
  const ActiveNodes a = ActiveNodes::of(g, NodeBox{Vec3i(0, 2, 1), Vec3i(9, 3, 2)});
  const std::vector<long> all = nodesOf(a.rows);
  for (int threads = 1; threads <= 7; ++threads) {
    std::vector<long> visited;
    std::vector<size_t> share;
    for (int t = 0; t < threads; ++t) {
      const size_t before = visited.size();
      forEachNodeOfThread(a.rows, t, threads, [&](long k) { visited.push_back(k); });
      share.push_back(visited.size() - before);
    }
    EXPECT_EQ(visited, all) << threads << " threads";
    for (size_t s : share) EXPECT_LE(s, all.size() / threads + 1) << threads << " threads";
  }
}

// The pieces forEachNodeRange hands out, on the threads OpenMP gives it, cover every node of the
// rows exactly once (the clearing of the grid's fields relies on it).
TEST(ActiveNodes, NodeRangesCoverEveryNodeOnce) {
  const Grid g = testGrid();
  const ActiveNodes a = ActiveNodes::of(g, NodeBox{Vec3i(1, 2, 1), Vec3i(5, 6, 3)});
  const std::vector<long> all = nodesOf(a.rows);
  const int maxThreads = omp_get_max_threads();
  for (int threads = 1; threads <= 3; ++threads) {
    omp_set_num_threads(threads);
    std::vector<int> visits(g.numNodes(), 0);
    forEachNodeRange(a.rows, [&](long begin, long end) {
      for (long k = begin; k < end; ++k) ++visits[k];  // each k on one thread only
    });
    for (long k = 0; k < static_cast<long>(visits.size()); ++k)
      EXPECT_EQ(visits[k], std::binary_search(all.begin(), all.end(), k) ? 1 : 0)
          << "node " << k << ", " << threads << " threads";
  }
  omp_set_num_threads(maxThreads);
}

}  // namespace
}  // namespace anode
