#include "Components/MPM/ReactiveFlow/FluxSurfaceArea.h"

#include <cmath>
#include <limits>
#include <unordered_map>

namespace anode {

namespace {

// Two unit vectors that make an orthonormal basis with the unit vector a.
std::pair<Vec3, Vec3> basisAround(const Vec3& a) {
  const Vec3 helper = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = a.cross(helper).normalized();
  return {u, a.cross(u)};
}

// Equal-area rings of the disk of radius R around `center` (normal n), samples at most
// `spacing` apart along each ring.
void sampleDisk(const Vec3& center, const Vec3& n, double R, double spacing,
                const SampleRegion& region, std::vector<SurfaceSample>& out) {
  const auto [u, v] = basisAround(n);
  const int rings = static_cast<int>(std::ceil(R / spacing));
  for (int k = 0; k < rings; ++k) {
    const double r0 = R * k / rings, r1 = R * (k + 1) / rings, r = 0.5 * (r0 + r1);
    const int around = std::max(1, static_cast<int>(std::ceil(2 * M_PI * r / spacing)));
    const double area = M_PI * (r1 * r1 - r0 * r0) / around;
    for (int i = 0; i < around; ++i) {
      const double theta = 2 * M_PI * (i + 0.5) / around;
      const Vec3 x = center + r * (std::cos(theta) * u + std::sin(theta) * v);
      if (region.keeps(x)) out.push_back({x, n, area});
    }
  }
}

// A Fibonacci lattice: N nearly evenly spread points, each standing for 1/N of the sphere.
void sampleSphere(const Vec3& center, double R, double spacing, const SampleRegion& region,
                  std::vector<SurfaceSample>& out) {
  const long n = std::max(1L, static_cast<long>(std::ceil(4 * M_PI * R * R / (spacing * spacing))));
  const double golden = M_PI * (3 - std::sqrt(5.0)), area = 4 * M_PI * R * R / n;
  for (long i = 0; i < n; ++i) {
    const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = golden * i;
    const Vec3 normal(r * std::cos(phi), r * std::sin(phi), z);
    if (region.keeps(center + R * normal)) out.push_back({center + R * normal, normal, area});
  }
}

void sampleCylinderSide(const Vec3& bottom, const Vec3& top, double R, double spacing,
                        const SampleRegion& region, std::vector<SurfaceSample>& out) {
  const Vec3 axis = top - bottom;
  const double L = axis.norm();
  const auto [u, v] = basisAround(axis / L);
  const int around = static_cast<int>(std::ceil(2 * M_PI * R / spacing));
  const int along = static_cast<int>(std::ceil(L / spacing));
  const double area = 2 * M_PI * R * L / (static_cast<double>(around) * along);
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      const double theta = 2 * M_PI * (i + 0.5) / around;
      const Vec3 normal = std::cos(theta) * u + std::sin(theta) * v;
      const Vec3 x = bottom + axis * ((j + 0.5) / along) + R * normal;
      if (region.keeps(x)) out.push_back({x, normal, area});
    }
}

// The six faces of a box, each a lattice of samples at most `spacing` apart.
void sampleBox(const Vec3& lo, const Vec3& hi, double spacing, const SampleRegion& region,
               std::vector<SurfaceSample>& out) {
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const double lb = hi[b] - lo[b], lc = hi[c] - lo[c];
    const int nb = std::max(1, static_cast<int>(std::ceil(lb / spacing)));
    const int nc = std::max(1, static_cast<int>(std::ceil(lc / spacing)));
    const double area = lb * lc / (static_cast<double>(nb) * nc);
    for (int side = 0; side < 2; ++side) {
      const Vec3 normal = (side == 0 ? -1.0 : 1.0) * Vec3::Unit(a);
      for (int j = 0; j < nc; ++j)
        for (int i = 0; i < nb; ++i) {
          Vec3 x;
          x[a] = side == 0 ? lo[a] : hi[a];
          x[b] = lo[b] + lb * (i + 0.5) / nb;
          x[c] = lo[c] + lc * (j + 0.5) / nc;
          if (region.keeps(x)) out.push_back({x, normal, area});
        }
    }
  }
}

// The surfaces of a piece's primitives (a union's, an intersection's or a difference's parts
// all); false for a piece without one here (a smoothcyl).
bool samplePiece(const GeometryPiece& piece, double spacing, const SampleRegion& region,
                 std::vector<SurfaceSample>& out) {
  if (const auto* box = dynamic_cast<const BoxPiece*>(&piece)) {
    sampleBox(box->lo, box->hi, spacing, region, out);
  } else if (const auto* cyl = dynamic_cast<const CylinderPiece*>(&piece)) {
    const Vec3 axis = (cyl->top - cyl->bottom).normalized();
    sampleCylinderSide(cyl->bottom, cyl->top, cyl->radius, spacing, region, out);
    sampleDisk(cyl->bottom, -axis, cyl->radius, spacing, region, out);
    sampleDisk(cyl->top, axis, cyl->radius, spacing, region, out);
  } else if (const auto* sphere = dynamic_cast<const SpherePiece*>(&piece)) {
    sampleSphere(sphere->origin, sphere->radius, spacing, region, out);
  } else if (const auto* u = dynamic_cast<const UnionPiece*>(&piece)) {
    for (const GeometryPieceP& part : u->pieces)
      if (!samplePiece(*part, spacing, region, out)) return false;
  } else if (const auto* i = dynamic_cast<const IntersectionPiece*>(&piece)) {
    for (const GeometryPieceP& part : i->pieces)
      if (!samplePiece(*part, spacing, region, out)) return false;
  } else if (const auto* d = dynamic_cast<const DifferencePiece*>(&piece)) {
    return samplePiece(*d->first, spacing, region, out) &&
           samplePiece(*d->second, spacing, region, out);
  } else {
    return false;
  }
  return true;
}

bool insideAny(const std::vector<GeometryPieceP>& pieces, const Vec3& x) {
  for (const GeometryPieceP& piece : pieces)
    if (piece->inside(x)) return true;
  return false;
}

// The flagged particles by grid cell, to find the one nearest a point among 27 cells.
class NearestParticle {
 public:
  NearestParticle(const Grid& grid, const ParticleSet& p, const std::vector<size_t>& flagged,
                  double reach)
      : grid_(grid), p_(p), flagged_(flagged), reach_(reach) {
    for (size_t k = 0; k < flagged.size(); ++k)
      cells_[key(cellOf(p.x[flagged[k]]))].push_back(static_cast<int>(k));
  }
  // The index into `flagged` of the particle nearest x within the reach (the lowest index of
  // equally near ones), -1 if none.
  int find(const Vec3& x) const {
    const Vec3i c = cellOf(x);
    int nearest = -1;
    double best = reach_ * reach_;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(key(c + Vec3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int k : it->second) {
            const double d2 = (p_.x[flagged_[k]] - x).squaredNorm();
            if (d2 < best || (d2 == best && k < nearest)) best = d2, nearest = k;
          }
        }
    return nearest;
  }

 private:
  Vec3i cellOf(const Vec3& x) const { return grid_.indexCoordinate(x).array().floor().cast<int>(); }
  long key(const Vec3i& c) const {  // cells -1 .. cells + 1 on each axis, without overlap
    const Vec3i n = grid_.cells + Vec3i::Constant(3);
    return (static_cast<long>(c.z() + 1) * n.y() + (c.y() + 1)) * n.x() + (c.x() + 1);
  }
  const Grid& grid_;
  const ParticleSet& p_;
  const std::vector<size_t>& flagged_;
  double reach_;
  std::unordered_map<long, std::vector<int>> cells_;
};

}  // namespace

std::vector<SurfaceSample> sampleSurface(const ScalarFluxBC& bc, double spacing,
                                         const SampleRegion& region) {
  std::vector<SurfaceSample> out;
  switch (bc.face) {
    case ScalarFluxBC::Face::Sphere:
      sampleSphere(bc.center, bc.radius, spacing, region, out);
      break;
    case ScalarFluxBC::Face::CylinderSide:
      sampleCylinderSide(bc.bottom, bc.top, bc.radius, spacing, region, out);
      break;
    case ScalarFluxBC::Face::CylinderEnd: {
      const Vec3 axis = (bc.top - bc.bottom).normalized();
      sampleDisk(bc.bottom, -axis, bc.radius, spacing, region, out);
      sampleDisk(bc.top, axis, bc.radius, spacing, region, out);
      break;
    }
    case ScalarFluxBC::Face::Box:      // a box face keeps the particle face it names
    case ScalarFluxBC::Face::Surface:  // its body's surface: shareBodySurface
      break;
  }
  return out;
}

SurfaceShare shareSurfaceArea(const ScalarFluxBC& bc, const std::vector<GeometryPieceP>& body,
                              const Grid& grid, const Vec3& dxp, const std::vector<size_t>& flagged,
                              const std::vector<int>& slot, ParticleSet& p,
                              const SampleRegion& region) {
  const DiffusionParticles d(p);
  for (size_t k = 0; k < flagged.size(); ++k) d.area[flagged[k]][slot[k]] = 0;
  const NearestParticle nearestOf(grid, p, flagged, 1.5 * dxp.norm());
  const double spacing = 0.25 * dxp.minCoeff(), offset = 1e-3 * dxp.minCoeff();
  SurfaceShare share;
  for (const SurfaceSample& s : sampleSurface(bc, spacing, region)) {
    const bool counted = region.counts(s.x);
    if (counted) share.surfaceArea += s.area;
    if ((s.x.array() < grid.lower.array()).any() || (s.x.array() > grid.upper.array()).any())
      continue;
    if (insideAny(body, s.x - offset * s.normal) == insideAny(body, s.x + offset * s.normal))
      continue;
    if (counted) share.bodyArea += s.area;
    const int nearest = nearestOf.find(s.x);
    if (nearest < 0) continue;
    d.area[flagged[nearest]][slot[nearest]] += s.area;
    if (counted) share.assignedArea += s.area;
  }
  return share;
}

bool shareBodySurface(const std::vector<GeometryPieceP>& body,
                      const std::vector<GeometryPieceP>& excluded, const Grid& grid,
                      const Vec3& dxp, const std::vector<size_t>& candidates, const ParticleSet& p,
                      std::vector<double>& area, SurfaceShare& share, const SampleRegion& region) {
  const double spacing = 0.25 * dxp.minCoeff(), offset = 1e-3 * dxp.minCoeff();
  std::vector<SurfaceSample> samples;
  for (const GeometryPieceP& piece : body)
    if (!samplePiece(*piece, spacing, region, samples)) return false;
  const NearestParticle nearestOf(grid, p, candidates, 1.5 * dxp.norm());
  area.assign(candidates.size(), 0.0);
  share = {};
  for (const SurfaceSample& s : samples) {
    const bool counted = region.counts(s.x);
    if (counted) share.surfaceArea += s.area;
    // Inside the grid, off its faces (a body's face on a symmetry plane is no surface).
    if ((s.x.array() <= (grid.lower.array() + offset)).any() ||
        (s.x.array() >= (grid.upper.array() - offset)).any())
      continue;
    const bool insideBelow = insideAny(body, s.x - offset * s.normal),
               insideAbove = insideAny(body, s.x + offset * s.normal);
    if (insideBelow == insideAbove) continue;  // inside the body or outside it: no surface
    // Against another material it names: the point half a particle spacing outside is in it.
    const Vec3 outward = insideBelow ? s.normal : Vec3(-s.normal);
    if (insideAny(excluded, s.x + 0.5 * dxp.minCoeff() * outward)) continue;
    if (counted) share.bodyArea += s.area;
    const int nearest = nearestOf.find(s.x);
    if (nearest < 0) continue;
    area[nearest] += s.area;
    if (counted) share.assignedArea += s.area;
  }
  return true;
}

}  // namespace anode
