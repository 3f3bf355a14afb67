// One <material> of <MaterialProperties><MPM>: density, constitutive model and its particles.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/ParticleSet.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/Geometry/ParticleFill.h"
#include "Core/Geometry/SmoothCylinder.h"
#include "Core/Grid/Grid.h"

namespace anode {

// What setup learns while reading a material and needs until its particles are in place: which
// <geom_object> lays out which particles (counted before any is stored, so that each rank fills
// only its part: docs/parallel.md, "Setup per box"; the diffusion subcomponent reads each
// object's initial concentration and finds the surface particles there), and the grid-filled
// pieces (checked against the grid once the face BCs are known). Setup only.
struct MaterialSeeds {
  // One <geom_object>: the particles it lays out, `total` of them, numbered from `firstId`;
  // those on this rank are [first, first + count) of the material's, laid out dx/res apart,
  // with their face areas (normal to x, y, z; for a smooth piece normal to r, r, axis, per
  // particle).
  struct Object {
    PSNode node;
    GeometryPieceP piece;  // the union of its pieces
    PSNode sizeNode;       // where a particle count beyond the memory budget is reported
    Vec3 velocity = Vec3::Zero();
    std::shared_ptr<const PieceLattice> lattice;  // a grid-filled object's points per cell
    std::vector<SmoothParticle> smoothLayout;     // a smooth one's particles, all of them
    int64_t total = 0, firstId = 0;
    size_t first = 0, count = 0;
    Vec3i res = Vec3i::Ones();          // particles per cell of a grid-filled object
    Vec3 spacing = Vec3::Zero();        // dx/res
    bool smooth = false;                // laid out by a <smoothcyl>
    Vec3 faceArea = Vec3::Zero();       // of every particle of a grid-filled object
    std::vector<Vec3> smoothFaceAreas;  // per particle of a smooth one on this rank

    Vec3 faceAreaOf(size_t i) const { return smooth ? smoothFaceAreas[i - first] : faceArea; }
    // Its particles in the cells of `region`.
    int64_t countIn(const Grid& grid, const CellBox& region) const;
    // Calls visit(x, V) for each particle it lays out (on every rank), in ID order, storing none.
    void forEachParticle(const Grid& grid,
                         const std::function<void(const Vec3&, double)>& visit) const;
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
  // Calls visit(x) with the position of each particle the objects lay out (on every rank), in
  // the order of their IDs, storing none.
  void forEachPosition(const Grid& grid, const std::function<void(const Vec3&)>& visit) const;
  // Calls visit(cell, particles) for the cells the objects lay particles in (a cell once per
  // object at most).
  void forEachOccupiedCell(const Grid& grid,
                           const std::function<void(const Vec3i&, double)>& visit) const;
};

struct MPMMaterial {
  std::string name;
  double density = 0;  // rho0; particle mass = rho0 * V0
  std::unique_ptr<ConstitutiveModel> model;
  ParticleSet particles;

  // Reads the material and counts the particles its geom_objects lay out, into `seeds`.
  static MPMMaterial fromInput(const PSNode& node, const Grid& grid, const MPMFlags& flags,
                               GeometryPieceFactory& pieces, MaterialSeeds& seeds);
  // Creates the particles of `seeds` (their firstId set) in the cells of `region`, each with the
  // ID it has when one rank holds them all.
  void placeParticles(MaterialSeeds& seeds, const Grid& grid, const CellBox& region);
};

// "[x, y, z]", for diagnostics.
std::string formatVector(const Vec3& v);
// "material M (name)", the name only if the input gave one, for diagnostics.
std::string describeMaterial(const MPMMaterial& mat, size_t matl);
// The particles of every material on this rank.
size_t countParticles(const std::vector<MPMMaterial>& materials);
// "particle ID of material M (name) at [x, y, z]", for diagnostics.
std::string describeParticle(const MPMMaterial& mat, size_t matl, size_t i);

}  // namespace anode
