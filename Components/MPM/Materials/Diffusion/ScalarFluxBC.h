// <PhysicalBC><MPM><scalar_flux> (UINTAH_UPS.md §2.9, §3.1, §5.1; paper Eqs. 16-17): a lithium
// flux J(t) through the surface particles a geometry piece selects. Surface particles are found
// once at the start; each flagged particle records, per load curve (at most 3), the area of the
// face that BC names. The rate of a particle is sum_k J_k(t) A_k / V_p times the restriction
// R(c) (applied once per particle).
#pragma once

#include <memory>
#include <vector>

#include "Components/MPM/ParticleSet.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"
#include "Core/Util/LoadCurve.h"

namespace anode {

// Eq. 17 with Uintah's clamp: max(0, 1 + ln(1 - c)/4) for normalised c; 0 for c >= 1.
double fluxRestriction(double c);
// The restriction of a flux into (inflow) or out of a particle at normalised c: R(c), or its
// mirror R(1 - c), which vanishes as the particle empties (docs/diffusion.md).
inline double fluxRestriction(double c, bool inflow) { return fluxRestriction(inflow ? c : 1 - c); }
// The restriction's steepest slope before it reaches zero, |R'| at c = 1 - e^-4: a particle
// whose unrestricted rate is k cannot step past the zero of R when dt k kRestrictionSlope <= 1.
constexpr double kRestrictionSlope = 13.649537508286059;  // e^4 / 4 = 13.649537508286059769...

struct ScalarFluxBC {
  enum class Face { Box, CylinderSide, CylinderEnd, Sphere } face = Face::Box;
  Vec3 boxMin, boxMax;          // box
  Vec3 bottom, top;             // cylinder
  double radius = 0;            // cylinder, sphere
  Vec3 center;                  // sphere
  LoadCurve load{{0.0}, {0.0}};
  int line = 0;

  static std::vector<ScalarFluxBC> fromInput(const PSNode& physicalBC);

  // The area of the face this BC names for a particle at x, selected with the spacing dxp;
  // faceAreas are the particle's face areas normal to x, y, z (for smooth pieces: normal to r,
  // r, axis). 0 if the BC does not flag it. Uintah's selection rules (UINTAH_UPS.md §3.1).
  double flaggedArea(const Vec3& x, const Vec3& dxp, const Vec3& faceAreas) const;
  // Unit normal of the face this BC names near x, and the distance of x from that face (for
  // sharing a flux face among split particles).
  Vec3 normalAt(const Vec3& x) const;
  double distanceToFace(const Vec3& x) const;
  // The same for an axis-aligned grid-filled particle of edge lengths dxp.
  double flaggedArea(const Vec3& x, const Vec3& dxp) const {
    return flaggedArea(x, dxp, Vec3(dxp.y() * dxp.z(), dxp.x() * dxp.z(), dxp.x() * dxp.y()));
  }
};

// Surface detection (UINTAH_UPS.md §3.1): any of x +- dxp_k e_k (k < ndim) outside the piece.
bool onSurface(const GeometryPiece& piece, const Vec3& x, const Vec3& dxp, int ndim);

}  // namespace anode
