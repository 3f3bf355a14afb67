// Uintah's "smooth" cylinder piece (UINTAH_UPS.md §3.2): instead of filling grid cells, it lays
// particles on rings (pie slices, or rings of about constant particle volume), each particle
// carrying its own volume, CPDI domain (size) and face areas, so the surface is smooth.
#pragma once

#include <vector>

#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

struct SmoothParticle {
  Vec3 x;
  double volume;
  Mat3 size;  // edge vectors in grid-cell units: tangential chord, radial thickness, axial length
  Vec3 faceArea;  // (outer face normal to r, the same, face normal to the axis)
};

struct SmoothCylinderPiece : GeometryPiece {
  enum class Scheme { PieSlices, ConstantParticleVolumes } scheme = Scheme::PieSlices;
  Vec3 bottom, top;
  double outerRadius = 0, innerRadius = 0;
  int numRadial = 1, numAxial = 1, numAngular = 0;
  double arcStart = 0;         // radians
  double arcAngle = 2 * M_PI;  // radians

  static std::shared_ptr<SmoothCylinderPiece> fromInput(const PSNode& node);

  bool inside(const Vec3& x) const override;
  std::string type() const override { return "smoothcyl"; }
  Bounds bounds() const override {
    return {bottom.cwiseMin(top).array() - outerRadius, bottom.cwiseMax(top).array() + outerRadius};
  }
  // How many particles createParticles lays out, counted up to `limit` (a larger count stops
  // the count: it returns a value above `limit`), without creating them.
  double particleCount(const Grid& grid, double limit) const;
  // Call only when particleCount() is within what the run can hold (counts fit an int).
  std::vector<SmoothParticle> createParticles(const Grid& grid) const;

 private:
  // Particles in ring ii of one axial layer.
  double slicesInRing(int ii, double cellVolume) const;
};

}  // namespace anode
