// SD-Type boundary conditions on the nodal concentration (UINTAH_UPS.md §5.3; docs/diffusion.md):
// Dirichlet sets the face nodes and the extra nodes beyond them to the value; Neumann sets them
// to their inward neighbour minus value*dx.
#pragma once

#include <vector>

#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"

namespace anode {

struct ConcentrationBC {
  BCFace face;
  enum class Kind { Dirichlet, Neumann } kind = Kind::Dirichlet;
  double value = 0;  // the concentration (Dirichlet) or its gradient (Neumann)

  // An SD-Type <BCType> of <Grid><BoundaryConditions> (ReactiveFlow::fromInput reads them).
  static ConcentrationBC fromInput(const BCType& bc);
  // The same in a run without diffusion: an error.
  [[noreturn]] static void rejectWithoutDiffusion(const BCType& bc);
};

void applyConcentrationBCs(const Grid& g, const std::vector<ConcentrationBC>& bcs, int matl,
                           std::vector<double>& field);

// Per material, per node: 1 on the nodes an SD-Type Dirichlet condition sets, 0 elsewhere (for
// the particle treatment of Dirichlet walls); empty when there is no such condition.
std::vector<std::vector<double>> dirichletNodeMasks(const Grid& g,
                                                    const std::vector<ConcentrationBC>& bcs,
                                                    size_t materials);

}  // namespace anode
