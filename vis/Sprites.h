// The particles one scene draws, reduced to what the GPU needs: a position, the field value and
// a radius per particle, nothing else (DESIGN.md §7).
#pragma once

#include <vector>

#include "vis/PointData.h"
#include "vis/SceneSpec.h"

namespace anode {

struct SpriteSet {
  std::vector<double> position;  // x0 y0 z0 x1 ...
  std::vector<double> value;     // the scene's field, times the scene's scale
  std::vector<double> radius;    // spriteRadius of the particle's volume
  size_t count() const { return value.size(); }
};

// Picks the particles the scene draws (its materials, its side of the clip plane) out of `data`,
// which holds the scene's field array and, when available, "p.volume" and "material" arrays
// (data without a material array is taken to hold only the scene's materials).
// Without p.volume every particle gets the radius of an equal share of the bounding box.
// Positions, field and volume are taken as single precision holds them, so that data stored as
// Float32 (writeParticlesVTU's VTUData::Picture) draws the same picture as the run's Float64.
// Throws std::runtime_error when the field array is missing or has the wrong component count.
// `drawn`, when given, receives each sprite's particle: its index in `data`.
// A particle's value as a picture draws it, before the scene's scale: the field of its tuple of
// field.components numbers, each and the result as single precision holds them.
double pictureValue(const FieldSpec& field, const double* tuple);

SpriteSet makeSprites(const Scene& scene, const ParticleData& data,
                      std::vector<size_t>* drawn = nullptr);

// The radius of the sphere of volume v.
double sphereRadius(double volume);
// The radius a particle of volume v is drawn with: the sphere around its cube (edge cbrt(v)),
// half the cube's diagonal, so the spheres of a solid block cover it from any side (the sphere of
// its own volume, 0.62 of the edge, leaves the background showing through at the lattice's
// corners where it is seen face-on).
double spriteRadius(double volume);

}  // namespace anode
