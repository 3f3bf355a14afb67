// <MaterialProperties><MPM><diffusion_interface>: null, each material diffuses on its own, or
// common, one mass-weighted concentration for all materials at a node (UINTAH_UPS.md §2.6).
#pragma once

#include <vector>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/ReactiveFlow/DiffusionGridFields.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct DiffusionInterface {
  bool common = false;  // and more than one material

  // `diffusion`: whether <do_scalar_diffusion> is on (common needs it).
  static DiffusionInterface fromInput(const PSNode& mpmMaterials, bool diffusion, size_t materials);

  // common: c_i = sum_m m_i c_i / sum_m m_i for every material, on the nodes of `nodes`.
  void apply(const std::vector<GridFields>& mechanics, std::vector<ConcentrationGridFields>& fields,
             const std::vector<NodeRange>& nodes) const;
};

}  // namespace anode
