// <PhysicalBC><MPM><scalar_flux> (UINTAH_UPS.md §2.9, §3.1, §5.1; paper Eqs. 16-17): a lithium
// flux J(t) through the surface particles a geometry piece selects. Surface particles are found
// once at the start; each flagged particle records, per load curve (at most 3), the area of the
// face that BC names. The rate of a particle is sum_k J_k(t) A_k / V_p times the restriction
// R(c) (applied once per particle). A galvanostatic BC prescribes instead the total lithium rate
// into its particles, and J_k follows from it each step (ExternalScalarFlux.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/ReactiveFlow/SurfaceReaction.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"
#include "Core/Util/LoadCurve.h"

namespace anode {

struct ScalarFluxBC {
  // Surface: <surface material="..." exclude="..."/>, the free surface of a material's body
  // (every grid-filled geom_object), less where another material it names lies against it.
  enum class Face { Box, CylinderSide, CylinderEnd, Sphere, Surface } face = Face::Box;
  std::string surfaceMaterial;        // Surface: the material's name
  std::vector<std::string> excluded;  // Surface: names of the materials it lies against
  Vec3 boxMin, boxMax;                // box
  Vec3 bottom, top;                   // cylinder
  double radius = 0;                  // cylinder, sphere
  Vec3 center;                        // sphere
  LoadCurve load{{0.0}, {0.0}};
  // <mode>flux (default, Eq. 16): the load is J, the flux through the surface. galvanostatic:
  // the load is the total lithium rate into the particles the BC flags, in history.csv's
  // lithium per time (mass x concentration / time), held until the flagged surface's mean
  // restriction falls to `cutoff` (a full surface takes no more: the BC's current ends there).
  // potentiostatic: the load is c_s, the surface concentration held through a surface reaction
  // of rate constant k (`surfaceRate`, <surface_rate>, length per time): J = k (c_s - c_p) / c_max
  // at each flagged particle (a Robin condition; kL/D >> 1 holds c_s), not restricted by R.
  enum class Mode { Flux, Galvanostatic, Potentiostatic } mode = Mode::Flux;
  double cutoff = 0.25;  // <cutoff>, galvanostatic only
  // <surface_reaction> (ours, galvanostatic only): the flux into each flagged particle follows
  // Butler-Volmer at the one potential that carries the BC's current (SurfaceReaction.h), and
  // the cutoffs are potentials; null: the flux is shared as a uniform J restricted by R(c).
  std::shared_ptr<const SurfaceReaction> reaction;
  double surfaceRate = 0;  // <surface_rate>, potentiostatic only
  // <rate_unit>C</rate_unit> (galvanostatic only): the load is a C-rate, n C filling the
  // materials the BC flags (every particle, to max_concentration) in 1/n of an hour, `hour`
  // (<hour>) being an hour in the input's time unit; 0: the load is in lithium per time.
  double hour = 0;
  // <area_update>deformed: a flagged particle's face area follows its deformation (Nanson);
  // constant (default, as Uintah): the area it was given at the start.
  bool deformedArea = false;
  // <area_rule>particle_face: a curved face on a body filled on the grid also gives each flagged
  // particle the particle face it names (Uintah's rule); surface (default): its share of the
  // BC's surface (FluxSurfaceArea.h).
  bool particleFaceArea = false;
  int line = 0;
  int geomLine = 0;  // of its <geom_object>

  // The <scalar_flux> blocks, in file order, which MPM's reader of <PhysicalBC> hands over.
  static std::vector<ScalarFluxBC> fromInput(const std::vector<PSNode>& blocks);

  // The area of the face this BC names for a particle at x, selected with the spacing dxp;
  // faceAreas are the particle's face areas normal to x, y, z (for smooth pieces: normal to r,
  // r, axis). 0 if the BC does not flag it. Uintah's selection rules (UINTAH_UPS.md §3.1).
  double flaggedArea(const Vec3& x, const Vec3& dxp, const Vec3& faceAreas) const;
  // Unit normal of the face this BC names near x, and the distance of x from that face (for
  // sharing a flux face among split particles).
  Vec3 normalAt(const Vec3& x) const;
  double distanceToFace(const Vec3& x) const;
  // The ratio of a particle face's current area to its area A0 at the start, J |F^-T N| (Nanson),
  // for deformation gradient F and N this BC's normal at the reference position X.
  double areaStretch(const Mat3& F, const Vec3& X) const;
  // The same for an axis-aligned grid-filled particle of edge lengths dxp.
  double flaggedArea(const Vec3& x, const Vec3& dxp) const {
    return flaggedArea(x, dxp, Vec3(dxp.y() * dxp.z(), dxp.x() * dxp.z(), dxp.x() * dxp.y()));
  }
};

// Surface detection (UINTAH_UPS.md §3.1): any of x +- dxp_k e_k (k < ndim) outside the piece.
bool onSurface(const GeometryPiece& piece, const Vec3& x, const Vec3& dxp, int ndim);

}  // namespace anode
