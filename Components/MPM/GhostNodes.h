// The nodes a rank shares with its neighbours (docs/parallel.md): after P2G each rank holds its
// own particles' part of the nodal sums on its window; the ranks whose windows overlap exchange
// those parts on the shared nodes and every holder adds them in rank order, so a shared node has
// the same complete sum, bit for bit, on every rank that stores it and the node-by-node grid
// tasks (contact, integration, boundary conditions) run on ghost nodes as on owned ones. A rank
// sends only the shared nodes its particles can reach this step (its reach box): elsewhere its
// part is zero; and only the shared nodes some rank reaches are summed.
#pragma once

#include <vector>

#include "Core/Grid/Grid.h"
#include "Core/Parallel/Communicator.h"
#include "Core/Parallel/Decomposition.h"

namespace anode {

// One nodal array as doubles: `width` per node (1 for a scalar, 3 for a Vec3).
struct NodeArray {
  double* values;
  int width;
};

// Nodes [first, last] (grid indices, inclusive); empty when first exceeds last on an axis.
struct NodeBox {
  Vec3i first = Vec3i::Zero(), last = -Vec3i::Ones();
  bool empty() const { return (first.array() > last.array()).any(); }
  NodeBox intersection(const NodeBox& b) const {
    return {first.cwiseMax(b.first), last.cwiseMin(b.last)};
  }
};

class GhostNodes {
 public:
  GhostNodes() = default;
  // The shared nodes of rank `rank` (window `local`) with its neighbours.
  GhostNodes(Collective, const Decomposition& d, const Grid& whole, const Grid& local, int rank,
             int ghost);

  bool empty() const { return neighbours_.ranks().empty(); }
  // This step's nodes: this rank's particles reach none outside `mine`. Returns the box holding
  // every rank's, outside which no rank has a part in any sum.
  NodeBox setReach(Collective, const NodeBox& mine);
  // Completes the sums of `arrays` on the shared nodes (each rank's part added in rank order),
  // after this step's setReach.
  void sumOverRanks(Collective, const std::vector<NodeArray>& arrays);
  // The bitwise OR of each rank's marks on the shared nodes, after this step's setReach.
  void unionOverRanks(Collective, std::vector<unsigned char>& marks) const;
  const std::vector<int>& neighbours() const { return neighbours_.ranks(); }
  const Neighbourhood& neighbourhood() const { return neighbours_; }

 private:
  Neighbourhood neighbours_;
  int rank_ = 0;
  Grid local_;
  std::vector<NodeBox> overlap_;  // per neighbour: the nodes both windows hold
  std::vector<int> sharedNodes_;  // local indices of every shared node, ascending
  std::vector<int> slotOfNode_;   // per local node: its place in sharedNodes_, or -1
  NodeBox reach_;                 // this step's, of this rank's particles
  NodeBox reachOfAll_;            // this step's, of every rank's particles
  std::vector<double> total_;     // per shared node: the sums being completed
};

}  // namespace anode
