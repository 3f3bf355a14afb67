// Whether a swelling body has room to grow (the setup half of SymmetryFaceWatch.h): per material
// that takes up lithium, its bodies (particles connected through the grid cells they occupy) and
// the Symmetric faces each would reach swelling freely to c = 1, exp(eta)-fold along each axis,
// away from what it rests on (a Symmetric face it starts on, another material just beyond it) or
// else about its middle. Computed at setup from where the geom_objects lay their particles out
// (MaterialSeeds: the same on every rank).
#pragma once

#include <string>
#include <vector>

#include "Components/MPM/GridBoundaryConditions.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Components/MPM/ReactiveFlow/ReactiveFlow.h"

namespace anode {

// A body: a material's particles connected through occupied cells (26 neighbours).
struct Body {
  size_t particles = 0;
  Vec3 lo, hi;                     // extent of its particle centres
  std::vector<std::string> faces;  // the Symmetric faces free swelling would carry it into
  // Per axis and side (0: minus): another material occupies a cell next to one of its cells.
  bool restsOnOther[3][2] = {};
};

// The bodies of material m, in the order of their first particle.
std::vector<Body> findBodies(const Grid& g, const std::vector<MaterialSeeds>& seeds, size_t m);

// The setup notes: per material whose bodies would reach a Symmetric face, which bodies reach
// which faces.
std::vector<std::string> swellingRoomNotes(const Grid& g, const GridBoundaryConditions& bcs,
                                           const std::vector<MPMMaterial>& materials,
                                           const std::vector<MaterialSeeds>& seeds,
                                           const ReactiveFlow* diffusion);

}  // namespace anode
