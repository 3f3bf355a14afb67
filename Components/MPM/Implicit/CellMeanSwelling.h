// The swelling an implicit step gives the particles with <swelling_strain>cell_mean
// (docs/quasi-static.md, "Swelling on cells"). A particle's stress update takes the swelling
// rate eta dc/dt on each normal component (RFElasticPlastic.h). Where c varies along one axis,
// as with depth in a film, the displacement of the grid's shape functions has one gradient
// along that axis per cell, so where c varies between the particles of a cell no displacement
// meets each one's swelling and their stresses part by layer: in a film, the stress normal to it
// alternates in sign from one layer of particles to the next though its mean is zero. Taken on
// the space the displacement can represent there, the concentration a particle's swelling
// follows is the volume-weighted mean of c over the cells its domain overlaps: the cell means
// S_c / W_c, S_c = sum_p w_pc V_p c_p, W_c = sum_p w_pc V_p, gathered back with the same
// overlaps w_pc (the share of the particle's box, its domain F size as an axis-aligned box in
// index space, in cell c). The particle keeps the cell-mean c its swelling has reached
// (p.swellingConcentration); a step's swelling is the cell mean of c at the step's end, on the
// step's start configuration, less that: a state, not a sum of smoothed increments, so it cannot
// drift from c over cycles. The projection keeps the sum of V c and changes nothing where c is
// uniform; c itself, and the lithium, stay the particles' own. In 3-D a trilinear displacement's
// normal strain also varies across a cell (along the other two axes), so a field varying in
// every direction loses to the staircase of cell means what it gains (the lithiated sphere).
#pragma once

#include <vector>

#include "Components/MPM/GhostNodes.h"
#include "Components/MPM/ParticleSet.h"
#include "Core/Grid/Grid.h"
#include "Core/Parallel/Communicator.h"

namespace anode {

// One material's particles `p` with `values` (one per particle): `mean` receives each particle's
// cell mean. The cell sums are held at each cell's lowest node and completed over the ranks
// through `ghosts` (null on one rank) on the shared nodes of the step's reach (an implicit step's
// reach is the rank's whole window, MPMWeights.cc). A cell is the material's own: two materials'
// particles in one cell do not share their means.
void cellMeanOf(Collective, const Grid& grid, GhostNodes* ghosts, const ParticleSet& p,
                const std::vector<double>& values, std::vector<double>& mean);

}  // namespace anode
