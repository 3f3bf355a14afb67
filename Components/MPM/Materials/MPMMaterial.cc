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

// Adds the particles of one <geom_object> (UINTAH_UPS.md §3.1).
void addGeomObject(const PSNode& geom, const Grid& grid, const MPMFlags& flags, MPMMaterial& m,
                   GeometryPieceFactory& pieces, int64_t& nextId, MaterialSeeds& out) {
  ParticleSet& p = m.particles;
  auto piece = std::make_shared<UnionPiece>();
  const std::vector<PSNode> pieceNodes = geom.childrenWhere(GeometryPieceFactory::isPieceTag);
  for (const PSNode& c : pieceNodes) piece->pieces.push_back(pieces.create(c));
  if (piece->pieces.empty())
    geom.fail("<geom_object> needs a geometry piece (box, cylinder, sphere, ...)");

  const PSNode resNode = geom.requireChild("res");
  const Vec3i res = resNode.value<Vec3i>();
  if ((res.array() < 1).any())
    resNode.fail("<res> needs at least one particle per cell in each direction");
  const Vec3 velocity = geom.require<Vec3>("velocity");
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
  std::vector<SmoothParticle> seeds;
  const Vec3 dxp = grid.dx.cwiseQuotient(res.cast<double>());
  const auto* smooth = piece->pieces.size() == 1
                           ? dynamic_cast<const SmoothCylinderPiece*>(piece->pieces[0].get())
                           : nullptr;
  // The particles of the materials before and of this object must fit the memory budget.
  const double limit = std::max(0.0, std::floor(maxParticles(flags)) - static_cast<double>(nextId));
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
    const double n = smooth->particleCount(grid, limit);
    if (n > limit)
      pieceNodes[0].fail("the <smoothcyl> lays out " +
                         (n > 2 * limit ? "more than " + formatCount(limit) : formatCount(n)) +
                         beyond);
    seeds = smooth->createParticles(grid);
  } else {
    for (const GeometryPieceP& g : piece->pieces)
      if (dynamic_cast<const SmoothCylinderPiece*>(g.get()))
        geom.fail("a <smoothcyl> must be the only piece of its <geom_object>");
    // Filling tests every candidate point: bound the work as well as the particles kept.
    const double candidates = fillCandidates(grid, *piece, res);
    if (candidates > 16 * limit + 1e6)
      resNode.fail("<res> gives " + formatCount(candidates) +
                   " candidate positions in the cells the pieces' bounding box meets; at most " +
                   formatCount(limit) + beyond);
    const std::vector<Vec3> points = fillParticles(grid, *piece, res, static_cast<size_t>(limit));
    if (static_cast<double>(points.size()) > limit)
      resNode.fail("the <geom_object> places more than " + formatCount(limit) + beyond);
    const Mat3 size = res.cast<double>().cwiseInverse().asDiagonal();
    const Vec3 faces(dxp.y() * dxp.z(), dxp.x() * dxp.z(), dxp.x() * dxp.y());  // normal to x, y, z
    for (const Vec3& x : points) seeds.push_back({x, dxp.prod(), size, faces});
  }
  // A smooth piece lays out every particle, inside the grid or not (grid-filled pieces are
  // checked once the face BCs are read: checkPiecesInsideGrid).
  if (smooth) {
    out.smooth = true;
    for (const SmoothParticle& s : seeds)
      if ((s.x.array() < grid.lower.array()).any() || (s.x.array() > grid.upper.array()).any())
        pieceNodes[0].fail("<smoothcyl> places particles outside " + domain(grid) + ", e.g. at " +
                           formatVector(s.x) + ": enlarge the <Grid><Box> or move the piece");
  } else {
    for (size_t k = 0; k < pieceNodes.size(); ++k)
      out.filledPieces.push_back({pieceNodes[k], piece->pieces[k], res});
  }
  if (seeds.empty())
    geom.fail(
        "<geom_object> places no particle: its pieces contain no particle position of the grid");

  const size_t first = p.count();
  MaterialSeeds::Object object{geom,         piece, first, seeds.size(), dxp, smooth != nullptr,
                               Vec3::Zero(), {}};
  if (smooth)
    for (const SmoothParticle& s : seeds) object.smoothFaceAreas.push_back(s.faceArea);
  else
    object.faceArea = seeds[0].faceArea;
  out.objects.push_back(std::move(object));
  p.resize(first + seeds.size());  // every array of the material's physics, at its initial value
  for (size_t k = 0; k < seeds.size(); ++k) {
    const SmoothParticle& s = seeds[k];
    const size_t i = first + k;
    p.id[i] = nextId++;
    p.x[i] = s.x;
    p.velocity[i] = velocity;
    p.mass[i] = m.density * s.volume;
    p.volume[i] = s.volume;
    p.size[i] = s.size;
  }
}

}  // namespace

std::string formatVector(const Vec3& v) {
  std::ostringstream s;
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

std::string describeMaterial(const MPMMaterial& mat, size_t matl) {
  return "material " + std::to_string(matl) + (mat.name.empty() ? "" : " (" + mat.name + ")");
}

std::string describeParticle(const MPMMaterial& mat, size_t matl, size_t i) {
  return "particle " + std::to_string(mat.particles.id[i]) + " of " + describeMaterial(mat, matl) +
         " at " + formatVector(mat.particles.x[i]);
}

MPMMaterial MPMMaterial::fromInput(const PSNode& node, const Grid& grid, const MPMFlags& flags,
                                   GeometryPieceFactory& pieces, int64_t& nextId,
                                   MaterialSeeds& seeds) {
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
  for (const PSNode& g : geoms) addGeomObject(g, grid, flags, m, pieces, nextId, seeds);
  const double lightest = *std::min_element(m.particles.mass.begin(), m.particles.mass.end());
  if (lightest <= flags.minimumParticleMass)
    node.requireChild("density").fail(
        "particle mass " + std::to_string(lightest) + " is at or below <minimum_particle_mass> " +
        std::to_string(flags.minimumParticleMass) + " (Uintah deletes such particles)");
  m.model->initializeState(m.particles);
  return m;
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
