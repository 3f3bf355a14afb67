// One <material> of <MaterialProperties><MPM>: density, constitutive model and its particles.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/ParticleSet.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

// What setup learns while filling a material's particles and needs once the rest of the input
// is read: which <geom_object> laid out which particles (for the subcomponents: the diffusion
// subcomponent reads its initial concentration and finds the surface particles there), and the
// grid-filled pieces (checked against the grid once the face BCs are known). Setup only.
struct MaterialSeeds {
  // One <geom_object>: its particles [first, first + count), laid out dx/res apart, with their
  // face areas (normal to x, y, z; for a smooth piece normal to r, r, axis, per particle).
  struct Object {
    PSNode node;
    GeometryPieceP piece;  // the union of its pieces
    size_t first = 0, count = 0;
    Vec3 spacing = Vec3::Zero();        // dx/res
    bool smooth = false;                // laid out by a <smoothcyl>
    Vec3 faceArea = Vec3::Zero();       // of every particle of a grid-filled object
    std::vector<Vec3> smoothFaceAreas;  // per particle of a smooth one

    Vec3 faceAreaOf(size_t i) const { return smooth ? smoothFaceAreas[i - first] : faceArea; }
  };
  std::vector<Object> objects;
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
  std::unique_ptr<ConstitutiveModel> model;
  ParticleSet particles;

  // Reads the material and fills its particles; `nextId` numbers particles across materials.
  // `seeds` receives what setup needs later.
  static MPMMaterial fromInput(const PSNode& node, const Grid& grid, const MPMFlags& flags,
                               GeometryPieceFactory& pieces, int64_t& nextId, MaterialSeeds& seeds);
};

// "[x, y, z]", for diagnostics.
std::string formatVector(const Vec3& v);
// "material M (name)", the name only if the input gave one, for diagnostics.
std::string describeMaterial(const MPMMaterial& mat, size_t matl);
// "particle ID of material M (name) at [x, y, z]", for diagnostics.
std::string describeParticle(const MPMMaterial& mat, size_t matl, size_t i);

}  // namespace anode
