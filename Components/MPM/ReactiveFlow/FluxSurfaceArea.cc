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
                std::vector<SurfaceSample>& out) {
  const auto [u, v] = basisAround(n);
  const int rings = static_cast<int>(std::ceil(R / spacing));
  for (int k = 0; k < rings; ++k) {
    const double r0 = R * k / rings, r1 = R * (k + 1) / rings, r = 0.5 * (r0 + r1);
    const int around = std::max(1, static_cast<int>(std::ceil(2 * M_PI * r / spacing)));
    const double area = M_PI * (r1 * r1 - r0 * r0) / around;
    for (int i = 0; i < around; ++i) {
      const double theta = 2 * M_PI * (i + 0.5) / around;
      out.push_back({center + r * (std::cos(theta) * u + std::sin(theta) * v), n, area});
    }
  }
}

}  // namespace

std::vector<SurfaceSample> sampleSurface(const ScalarFluxBC& bc, double spacing) {
  std::vector<SurfaceSample> out;
  switch (bc.face) {
    case ScalarFluxBC::Face::Sphere: {
      // A Fibonacci lattice: N nearly evenly spread points, each standing for 1/N of the sphere.
      const double R = bc.radius;
      const long n =
          std::max(1L, static_cast<long>(std::ceil(4 * M_PI * R * R / (spacing * spacing))));
      const double golden = M_PI * (3 - std::sqrt(5.0)), area = 4 * M_PI * R * R / n;
      out.reserve(n);
      for (long i = 0; i < n; ++i) {
        const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = golden * i;
        const Vec3 normal(r * std::cos(phi), r * std::sin(phi), z);
        out.push_back({bc.center + R * normal, normal, area});
      }
      break;
    }
    case ScalarFluxBC::Face::CylinderSide: {
      const Vec3 axis = bc.top - bc.bottom;
      const double L = axis.norm(), R = bc.radius;
      const auto [u, v] = basisAround(axis / L);
      const int around = static_cast<int>(std::ceil(2 * M_PI * R / spacing));
      const int along = static_cast<int>(std::ceil(L / spacing));
      const double area = 2 * M_PI * R * L / (static_cast<double>(around) * along);
      for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {
          const double theta = 2 * M_PI * (i + 0.5) / around;
          const Vec3 normal = std::cos(theta) * u + std::sin(theta) * v;
          out.push_back({bc.bottom + axis * ((j + 0.5) / along) + R * normal, normal, area});
        }
      break;
    }
    case ScalarFluxBC::Face::CylinderEnd: {
      const Vec3 axis = (bc.top - bc.bottom).normalized();
      sampleDisk(bc.bottom, -axis, bc.radius, spacing, out);
      sampleDisk(bc.top, axis, bc.radius, spacing, out);
      break;
    }
    case ScalarFluxBC::Face::Box:
      break;  // a box face keeps the particle face it names (docs/diffusion.md)
  }
  return out;
}

SurfaceShare shareSurfaceArea(const ScalarFluxBC& bc, const std::vector<GeometryPieceP>& body,
                              const Grid& grid, const Vec3& dxp, const std::vector<size_t>& flagged,
                              const std::vector<int>& slot, ParticleSet& p) {
  // The flagged particles by grid cell, to find the nearest of a sample among 27 cells.
  const auto cellOf = [&](const Vec3& x) -> Vec3i {
    return grid.indexCoordinate(x).array().floor().cast<int>();
  };
  const auto key = [&](const Vec3i& c) {  // cells -1 .. cells + 1 on each axis, without overlap
    const Vec3i n = grid.cells + Vec3i::Constant(3);
    return (static_cast<long>(c.z() + 1) * n.y() + (c.y() + 1)) * n.x() + (c.x() + 1);
  };
  const DiffusionParticles d(p);
  std::unordered_map<long, std::vector<int>> cells;
  for (size_t k = 0; k < flagged.size(); ++k) {
    cells[key(cellOf(p.x[flagged[k]]))].push_back(static_cast<int>(k));
    d.area[flagged[k]][slot[k]] = 0;
  }
  const auto insideBody = [&](const Vec3& x) {
    for (const GeometryPieceP& piece : body)
      if (piece->inside(x)) return true;
    return false;
  };
  const double spacing = 0.25 * dxp.minCoeff(), offset = 1e-3 * dxp.minCoeff(),
               reach = 1.5 * dxp.norm();
  SurfaceShare share;
  for (const SurfaceSample& s : sampleSurface(bc, spacing)) {
    share.surfaceArea += s.area;
    if ((s.x.array() < grid.lower.array()).any() || (s.x.array() > grid.upper.array()).any())
      continue;
    if (insideBody(s.x - offset * s.normal) == insideBody(s.x + offset * s.normal)) continue;
    share.bodyArea += s.area;
    const Vec3i c = cellOf(s.x);
    int nearest = -1;
    double best = reach * reach;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find(key(c + Vec3i(dx, dy, dz)));
          if (it == cells.end()) continue;
          for (int k : it->second) {
            const double d2 = (p.x[flagged[k]] - s.x).squaredNorm();
            if (d2 < best || (d2 == best && k < nearest)) best = d2, nearest = k;
          }
        }
    if (nearest < 0) continue;
    d.area[flagged[nearest]][slot[nearest]] += s.area;
    share.assignedArea += s.area;
  }
  return share;
}

}  // namespace anode
