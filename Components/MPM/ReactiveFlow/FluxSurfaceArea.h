// The flux area of grid-filled particles under a curved <scalar_flux> face (sphere, cylinder
// side and end; docs/diffusion.md, "Flux area at the start"). A particle face's area is right
// only where the surface faces a grid axis: on a curved surface the surface particles the BC
// flags form a layer whose thickness, and so their number per unit of surface, depends on how
// the surface faces the grid (a sphere filled on the lattice got 0.81 of 4 pi R^2). Instead the
// BC's own surface is sampled (points about dx/4 apart, each carrying its share of the area),
// a sample is kept where the material's body has its surface there, and its area goes to the
// nearest flagged particle: the flagged areas add up to the area of the flagged part of the
// body, whatever way it faces the grid.
#pragma once

#include <vector>

#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Components/MPM/ReactiveFlow/ScalarFluxBC.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

// A point of a flux BC's surface with the area it stands for and the surface's unit normal.
struct SurfaceSample {
  Vec3 x, normal;
  double area;
};

// The samples of a surface a process handles (setup per box, docs/parallel.md): it keeps those
// whose cell (the nearest interior cell for a point outside the grid) lies in `kept` (its box and
// the cells around it whose particles samples near its box can go to), and adds up the areas of
// those in `counted` (its box), so that each sample's area is added by one process. Without a
// grid, every sample is kept and counted (one process).
struct SampleRegion {
  const Grid* grid = nullptr;
  CellBox kept, counted;
  bool keeps(const Vec3& x) const { return !grid || kept.contains(grid->interiorCell(x)); }
  bool counts(const Vec3& x) const { return !grid || counted.contains(grid->interiorCell(x)); }
};

// Samples the surface of a sphere or cylinder BC (both end disks for cylinder_end) with points
// at most `spacing` apart, those `region` keeps; the areas of all add up to the surface's area.
std::vector<SurfaceSample> sampleSurface(const ScalarFluxBC& bc, double spacing,
                                         const SampleRegion& region = {});

// What distributing one BC's surface over one material's flagged particles gave (the areas of
// the samples the region counts).
struct SurfaceShare {
  double surfaceArea = 0;   // of the whole BC surface
  double bodyArea = 0;      // of the part where the body has its surface inside the grid
  double assignedArea = 0;  // of that part, handed to flagged particles
};

// Sets area[i][slot[k]] of each flagged particle flagged[k] to its share of the BC's surface on
// the body (`body`: the material's pieces). A sample goes to the nearest flagged particle within
// 1.5 |dxp| of it; a sample with none is not handed out (assignedArea < bodyArea).
SurfaceShare shareSurfaceArea(const ScalarFluxBC& bc, const std::vector<GeometryPieceP>& body,
                              const Grid& grid, const Vec3& dxp, const std::vector<size_t>& flagged,
                              const std::vector<int>& slot, ParticleSet& p,
                              const SampleRegion& region);

// The free surface of a material's body (a <surface> BC): the surfaces of its pieces are sampled
// (points about dxp/4 apart), a sample kept where the body has its surface there, inside the
// grid and not on a grid face (a symmetry plane is no surface), and not against a piece of
// `excluded` (another material lying on it); its area goes to the nearest of `candidates` (the
// material's surface particles) within 1.5 |dxp|. Returns each candidate's area; `share` gets
// the sums. False if a piece's surface cannot be sampled (a smoothcyl).
bool shareBodySurface(const std::vector<GeometryPieceP>& body,
                      const std::vector<GeometryPieceP>& excluded, const Grid& grid,
                      const Vec3& dxp, const std::vector<size_t>& candidates, const ParticleSet& p,
                      std::vector<double>& area, SurfaceShare& share, const SampleRegion& region);

}  // namespace anode
