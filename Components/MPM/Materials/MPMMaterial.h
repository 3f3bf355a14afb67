// One <material> of <MaterialProperties><MPM>: density, constitutive model and its particles.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/ParticleSet.h"
#include "Components/MPM/ReactiveFlow/ScalarDiffusionModel.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

// What setup learns while filling a material's particles and needs once the rest of the input
// is read: which particles lie on the surface of their geometry (for the flux BCs), and the
// grid-filled pieces (checked against the grid once the face BCs are known). Setup only.
struct MaterialSeeds {
  // Per particle: on the surface, its face areas (normal to x, y, z; for smooth pieces normal to
  // r, r, axis) and the spacing the flux BCs select it with (only with flux BCs possible).
  std::vector<uint8_t> onSurface;
  std::vector<Vec3> faceArea, spacing;
  // The grid-filled pieces of the geom_objects with their <res>.
  struct FilledPiece {
    PSNode node;
    GeometryPieceP piece;
    Vec3i res;
  };
  std::vector<FilledPiece> filledPieces;
  bool smooth = false;  // a <smoothcyl> laid out particles (on its surface, with their own areas)

  // An error at the first piece whose particle lattice reaches beyond the grid, where they are
  // dropped, other than beyond a face `mirror` marks (a symmetry BC for this material, index
  // 2 axis + side): a piece crossing a symmetry plane models half of a symmetric body.
  void checkPiecesInsideGrid(const Grid& grid, const std::array<bool, 6>& mirror) const;
};

struct MPMMaterial {
  std::string name;
  double density = 0;  // rho0; particle mass = rho0 * V0
  // <do_conc_reduction>: its particles count in the concentration <do_auto_cycle_bc> watches.
  bool reducesConcentration = false;
  std::unique_ptr<ConstitutiveModel> model;
  std::unique_ptr<ScalarDiffusionModel> diffusion;  // only with <do_scalar_diffusion>true
  ParticleSet particles;

  // Reads the material and fills its particles; `nextId` numbers particles across materials.
  // `maxTime` bounds the diffusion model's diff_curve. `seeds` receives what setup needs later.
  static MPMMaterial fromInput(const PSNode& node, const Grid& grid, const MPMFlags& flags,
                               double maxTime, GeometryPieceFactory& pieces, int64_t& nextId,
                               MaterialSeeds& seeds);
};

// "[x, y, z]", for diagnostics.
std::string formatVector(const Vec3& v);
// "material M (name)", the name only if the input gave one, for diagnostics.
std::string describeMaterial(const MPMMaterial& mat, size_t matl);
// "particle ID of material M (name) at [x, y, z]", for diagnostics.
std::string describeParticle(const MPMMaterial& mat, size_t matl, size_t i);

}  // namespace anode
