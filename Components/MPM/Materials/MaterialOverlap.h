// Two materials filled into the same space at setup (a pillar sunk into its substrate): each
// keeps its particles there, as in Uintah, so the space holds both masses. Not an error (an
// input may mean it), but rarely meant: a warning per pair at the later material's geom_object.
#pragma once

#include <vector>

#include "Components/MPM/Materials/MPMMaterial.h"

namespace anode {

struct MaterialOverlap {
  size_t first, second;  // material indices, first < second
  // The particles of each lying inside the other's geom_objects, and their volume.
  size_t firstInSecond = 0, secondInFirst = 0;
  double firstVolume = 0, secondVolume = 0;
  PSNode at;  // the second's first geom_object holding overlapping particles (or its first)
};

// The overlapping pairs, in material order, from where the geom_objects lay their particles out
// (the same on every rank).
std::vector<MaterialOverlap> findOverlaps(const Grid& grid,
                                          const std::vector<MaterialSeeds>& seeds);

// Adds the input warning of each overlap (PSNode::warn, at the second material's first
// geom_object that holds overlapping particles).
void warnOfOverlaps(const Grid& grid, const std::vector<MPMMaterial>& materials,
                    const std::vector<MaterialSeeds>& seeds);

}  // namespace anode
