// Pieces of the .ups texts the verification problems (VibratingBar.h, FluxSlab.h,
// DiffusionSlab1D.h) build in memory: one material, a bar or slab along x from the origin, two
// particles per cell along it, on a box grid from the origin, run from 0 to an end time with
// Simulation::advance (which writes no output). Each piece is whole lines, indented for its place.
#pragma once

#include <string>

#include "Core/ProblemSpec/UpsText.h"

namespace anode {

// Throws std::invalid_argument("<problem>: interpolator must be linear, gimp or cpdi").
void requireInterpolator(const std::string& problem, const std::string& interpolator);

// The XML declaration, `comment` as an XML comment, and the opening of the specification: its
// title and the <SimulationComponent> ("mpm" or "amrmpm").
std::string upsOpening(const std::string& comment, const std::string& title,
                       const std::string& component);
// <Time> from 0, its last step landing on endTime, dt at most maxDt (the first step firstDt when
// above 0), and a <DataArchiver> writing to `filebase` at a step interval no study reaches.
std::string upsTimeAndArchiver(double endTime, double maxDt, double multiplier,
                               const std::string& filebase, double firstDt = 0);
// <MPM>: `integrator` ("explicit" or "implicit") with `interpolator`, then `options` (whole
// lines).
std::string upsMPM(const std::string& interpolator, const std::string& options,
                   const std::string& integrator = "explicit");
// <PhysicalConstants> with `gravity` ("[gx,gy,gz]"), then <MaterialProperties> with `material`
// (whole lines), null contact and `more` (whole lines).
std::string upsMaterialProperties(const std::string& material, const std::string& more,
                                  const std::string& gravity = "[0,0,0]");
// A hypoelastic rf_elastic_plastic <constitutive_model>; with `diffuses`, swelling switched off.
std::string upsElasticModel(double bulkModulus, double shearModulus, bool diffuses);
// The <geom_object>: a box from the origin to [length, width, width], res [2,1,1], at rest at
// `temperature`; with `diffuses`, free of lithium.
std::string upsParticleBox(const std::string& label, double length, double width,
                           double temperature, bool diffuses);
// A <Face> whose only BC is Symmetric.
std::string upsSymmetricFace(const std::string& side);
// <Grid>: `faces` (whole lines) and one level, one box from the origin to [length, width, width]
// with cellsAlong x cells by cellsAcross in y and z, and `extraCells` ("[i,j,k]").
std::string upsGrid(const std::string& faces, double length, double width, int cellsAlong,
                    int cellsAcross, const std::string& extraCells);

// <Grid> for the octant of a sphere of `radius` centred at the origin, `cells` cells per radius:
// Symmetric faces x-, y-, z- through the centre, a box of cells + 2 cells per axis (room beyond
// the surface for the supports of the outermost particles), extra cells but for `linear`.
std::string upsSphereOctantGrid(double radius, int cells, const std::string& interpolator);

}  // namespace anode
