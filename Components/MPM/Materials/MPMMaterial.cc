#include "Components/MPM/Materials/MPMMaterial.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Components/MPM/ProblemSize.h"
#include "Core/Geometry/ParticleFill.h"
#include "Core/Geometry/SmoothCylinder.h"
#include "Core/Util/MemoryBudget.h"

namespace anode {

namespace {

std::string domain(const Grid& grid) {
  return "the grid domain " + formatVector(grid.lower) + " to " + formatVector(grid.upper);
}

// Reads one <geom_object> (UINTAH_UPS.md §3.1) and counts the particles it lays out.
void readGeomObject(const PSNode& geom, const Grid& grid, const MPMFlags& flags,
                    GeometryPieceFactory& pieces, MaterialSeeds& out) {
  auto piece = std::make_shared<UnionPiece>();
  const std::vector<PSNode> pieceNodes = geom.childrenWhere(GeometryPieceFactory::isPieceTag);
  for (const PSNode& c : pieceNodes) piece->pieces.push_back(pieces.create(c));
  if (piece->pieces.empty())
    geom.fail("<geom_object> needs a geometry piece (box, cylinder, sphere, ...)");

  const PSNode resNode = geom.requireChild("res");
  const Vec3i res = resNode.value<Vec3i>();
  if ((res.array() < 1).any())
    resNode.fail("<res> needs at least one particle per cell in each direction");
  MaterialSeeds::Object object;
  object.node = geom;
  object.piece = piece;
  object.velocity = geom.require<Vec3>("velocity");
  object.res = res;
  object.spacing = grid.dx.cwiseQuotient(res.cast<double>());
  // Temperature and colour change nothing in isothermal single-field MPM (the concentration is
  // the diffusion subcomponent's: ReactiveFlow).
  for (const char* inert : {"temperature", "color"}) geom.acceptInert(inert);
  if (const PSNode levels = geom.child("numLevelsParticleFilling"))
    if (levels.value<int>() != 1) levels.unsupported("multi-level particle filling");
  for (const char* affine : {"affineTransformation_A0", "affineTransformation_A1",
                             "affineTransformation_A2", "affineTransformation_b"})
    if (const PSNode a = geom.child(affine))
      a.unsupported("affine transformation of the particle lattice");

  // Particles from the grid (Uintah's placement) or laid out by a smooth piece.
  const auto* smooth = piece->pieces.size() == 1
                           ? dynamic_cast<const SmoothCylinderPiece*>(piece->pieces[0].get())
                           : nullptr;
  // Counting a piece's particles is bounded by the memory budget as well: a smooth piece's are
  // all laid out on every rank, a filled piece's candidate points are all tested.
  const double limit = std::floor(maxParticles(flags));
  const std::string beyond = " particles, beyond " + describeMemoryBudget() + " at about " +
                             std::to_string(static_cast<long>(bytesPerParticle(flags))) +
                             " bytes per particle";
  // Uintah scales a filled particle's mass by the volume fraction (-1, the default, means 1); a
  // smooth piece's particles get rho V whatever it says.
  if (const PSNode fraction = geom.child("volumeFraction")) {
    const double f = fraction.value<double>();
    if (!smooth && f != -1 && f != 1)
      fraction.unsupported("<volumeFraction> other than 1 (Uintah scales the particle mass by it)");
  }
  if (smooth) {
    object.sizeNode = pieceNodes[0];
    const double n = smooth->particleCount(grid, limit);
    if (n > limit)
      pieceNodes[0].fail("the <smoothcyl> lays out " +
                         (n > 2 * limit ? "more than " + formatCount(limit) : formatCount(n)) +
                         beyond);
    object.smoothLayout = smooth->createParticles(grid);
    // A smooth piece lays out every particle, inside the grid or not (grid-filled pieces are
    // checked once the face BCs are read: checkPiecesInsideGrid).
    for (const SmoothParticle& s : object.smoothLayout)
      if ((s.x.array() < grid.lower.array()).any() || (s.x.array() > grid.upper.array()).any())
        pieceNodes[0].fail("<smoothcyl> places particles outside " + domain(grid) + ", e.g. at " +
                           formatVector(s.x) + ": enlarge the <Grid><Box> or move the piece");
    object.smooth = out.smooth = true;
    object.total = static_cast<int64_t>(object.smoothLayout.size());
  } else {
    for (const GeometryPieceP& g : piece->pieces)
      if (dynamic_cast<const SmoothCylinderPiece*>(g.get()))
        geom.fail("a <smoothcyl> must be the only piece of its <geom_object>");
    object.sizeNode = resNode;
    // Filling tests every candidate point: bound the work as well as the particles kept.
    const double candidates = fillCandidates(grid, *piece, res);
    if (candidates > 16 * limit + 1e6)
      resNode.fail("<res> gives " + formatCount(candidates) +
                   " candidate positions in the cells the pieces' bounding box meets; at most " +
                   formatCount(limit) + beyond);
    object.lattice = std::make_shared<PieceLattice>(grid, piece, res);
    object.total = object.lattice->count();
    object.faceArea =
        Vec3(object.spacing.y() * object.spacing.z(), object.spacing.x() * object.spacing.z(),
             object.spacing.x() * object.spacing.y());  // normal to x, y, z
    for (size_t k = 0; k < pieceNodes.size(); ++k)
      out.filledPieces.push_back({pieceNodes[k], piece->pieces[k], res});
  }
  if (object.total == 0)
    geom.fail(
        "<geom_object> places no particle: its pieces contain no particle position of the grid");
  out.objects.push_back(std::move(object));
}

// The particles of `object` in the cells of `region`: positions, sizes and volumes, and each
// one's place in the object's order.
std::vector<SmoothParticle> objectParticles(const MaterialSeeds::Object& object, const Grid& grid,
                                            const CellBox& region, std::vector<int64_t>& place) {
  std::vector<SmoothParticle> particles;
  if (object.smooth) {
    for (size_t k = 0; k < object.smoothLayout.size(); ++k)
      if (region.contains(grid.interiorCell(object.smoothLayout[k].x))) {
        particles.push_back(object.smoothLayout[k]);
        place.push_back(static_cast<int64_t>(k));
      }
    return particles;
  }
  std::vector<Vec3> x;
  object.lattice->fill(region, x, place);
  const Mat3 size = object.res.cast<double>().cwiseInverse().asDiagonal();
  for (const Vec3& point : x)
    particles.push_back({point, object.spacing.prod(), size, object.faceArea});
  return particles;
}

}  // namespace

int64_t MaterialSeeds::Object::countIn(const Grid& grid, const CellBox& region) const {
  if (!smooth) return lattice->countIn(region);
  return std::count_if(smoothLayout.begin(), smoothLayout.end(), [&](const SmoothParticle& s) {
    return region.contains(grid.interiorCell(s.x));
  });
}

void MaterialSeeds::Object::forEachParticle(
    const Grid& grid, const std::function<void(const Vec3&, double)>& visit) const {
  if (smooth) {
    for (const SmoothParticle& s : smoothLayout) visit(s.x, s.volume);
    return;
  }
  const double volume = spacing.prod();
  lattice->forEachPoint({Vec3i::Zero(), grid.cells},
                        [&](const Vec3& x, int64_t) { visit(x, volume); });
}

void MaterialSeeds::forEachPosition(const Grid& grid,
                                    const std::function<void(const Vec3&)>& visit) const {
  for (const Object& object : objects)
    object.forEachParticle(grid, [&](const Vec3& x, double) { visit(x); });
}

void MaterialSeeds::forEachOccupiedCell(
    const Grid& grid, const std::function<void(const Vec3i&, double)>& visit) const {
  for (const Object& object : objects)
    if (object.smooth)
      for (const SmoothParticle& s : object.smoothLayout) visit(grid.interiorCell(s.x), 1.0);
    else
      object.lattice->forEachOccupiedCell(visit);
}

std::string formatVector(const Vec3& v) {
  std::ostringstream s;
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

std::string describeMaterial(const MPMMaterial& mat, size_t matl) {
  return "material " + std::to_string(matl) + (mat.name.empty() ? "" : " (" + mat.name + ")");
}

size_t countParticles(const std::vector<MPMMaterial>& materials) {
  size_t n = 0;
  for (const MPMMaterial& mat : materials) n += mat.particles.count();
  return n;
}

std::string describeParticle(const MPMMaterial& mat, size_t matl, size_t i) {
  return "particle " + std::to_string(mat.particles.id[i]) + " of " + describeMaterial(mat, matl) +
         " at " + formatVector(mat.particles.x[i]);
}

MPMMaterial MPMMaterial::fromInput(const PSNode& node, const Grid& grid, const MPMFlags& flags,
                                   GeometryPieceFactory& pieces, MaterialSeeds& seeds) {
  MPMMaterial m;
  m.name = node.attribute("name").value_or("");
  m.density = node.require<double>("density");
  if (!(m.density > 0)) node.requireChild("density").fail("<density> must be positive");
  for (const char* inert :
       {"thermal_conductivity", "specific_heat", "melt_temp", "room_temp", "C_p"})
    node.acceptInert(inert);
  if (const PSNode rigid = node.child("is_rigid"))
    if (rigid.value<bool>()) rigid.unsupported("rigid materials <is_rigid>");
  m.model =
      createConstitutiveModel(node.requireChild("constitutive_model"), flags.doScalarDiffusion);

  const auto geoms = node.children("geom_object");
  if (geoms.empty()) node.fail("<material> needs at least one <geom_object>");
  for (const PSNode& g : geoms) readGeomObject(g, grid, flags, pieces, seeds);
  // Every particle of a grid-filled object has the same volume; a smooth one's vary.
  double lightest = HUGE_VAL;
  for (const MaterialSeeds::Object& object : seeds.objects)
    if (object.smooth)
      for (const SmoothParticle& s : object.smoothLayout)
        lightest = std::min(lightest, m.density * s.volume);
    else
      lightest = std::min(lightest, m.density * object.spacing.prod());
  if (lightest <= flags.minimumParticleMass)
    node.requireChild("density").fail(
        "particle mass " + std::to_string(lightest) + " is at or below <minimum_particle_mass> " +
        std::to_string(flags.minimumParticleMass) + " (Uintah deletes such particles)");
  return m;
}

void MPMMaterial::placeParticles(MaterialSeeds& seeds, const Grid& grid, const CellBox& region) {
  ParticleSet& p = particles;
  for (MaterialSeeds::Object& object : seeds.objects) {
    std::vector<int64_t> place;
    const std::vector<SmoothParticle> placed = objectParticles(object, grid, region, place);
    object.first = p.count();
    object.count = placed.size();
    if (object.smooth)
      for (const SmoothParticle& s : placed) object.smoothFaceAreas.push_back(s.faceArea);
    p.resize(object.first + placed.size());  // every array of the physics, at its initial value
    for (size_t k = 0; k < placed.size(); ++k) {
      const SmoothParticle& s = placed[k];
      const size_t i = object.first + k;
      p.id[i] = object.firstId + place[k];
      p.x[i] = s.x;
      p.velocity[i] = object.velocity;
      p.mass[i] = density * s.volume;
      p.volume[i] = s.volume;
      p.size[i] = s.size;
    }
  }
  model->initializeState(p);
}

void MaterialSeeds::checkPiecesInsideGrid(const Grid& grid,
                                          const std::array<bool, 6>& mirror) const {
  // Uintah fills only the interior cells and drops the rest of a piece without a word.
  for (const FilledPiece& f : filledPieces)
    if (placesParticlesOutside(grid, *f.piece, f.res, mirror))
      f.node.fail("<" + f.node.name() + "> places particles outside " + domain(grid) +
                  ", beyond a face without a Symmetric BC, where they would be dropped: enlarge "
                  "the <Grid><Box> or trim the piece");
}

}  // namespace anode
