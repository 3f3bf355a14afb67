// One <material> of <MaterialProperties><MPM>: density, constitutive model and its particles.
#pragma once

#include <memory>
#include <string>

#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/ParticleSet.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

struct MPMMaterial {
  std::string name;
  double density = 0;  // rho0; particle mass = rho0 * V0
  std::unique_ptr<ConstitutiveModel> model;
  ParticleSet particles;

  // Reads the material and fills its particles; `nextId` numbers particles across materials.
  static MPMMaterial fromInput(const PSNode& node, const Grid& grid, const MPMFlags& flags,
                               GeometryPieceFactory& pieces, int64_t& nextId);
};

}  // namespace anode
