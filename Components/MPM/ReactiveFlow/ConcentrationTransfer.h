// What the diffusion of a quasi-static step (DiffusionPass.h) asks of the grid it runs on: MPM's
// transfers of the concentration between the particles, which stay where the step began, and
// the nodes, on the step's weights; the implicit integrator hands them over.
#pragma once

#include <cstddef>
#include <vector>

#include "Components/MPM/Interpolator.h"
#include "Core/Parallel/Communicator.h"

namespace anode {

class ConcentrationTransfer {
 public:
  virtual ~ConcentrationTransfer() = default;
  // P2G of the concentration's sums alone over the particles' c (the step's other sums stand),
  // completed on the nodes shared with other ranks.
  virtual void scatterConcentration(Collective) = 0;
  // Eq. 5 and the diffusion interface; `withVelocity`: the nodal velocity as well (after the
  // step's full P2G).
  virtual void computeNodalConcentration(bool withVelocity) = 0;
  // Eq. 18 over dt: c* and the nodal rate.
  virtual void integrateConcentration(double dt) = 0;
  // G2P of c alone (Eq. 8): material m's particles' change of c over dt, added to `change`.
  virtual void gatherConcentrationChange(size_t m, double dt, std::vector<double>& change) = 0;
  // grad c of material m's particles from the nodal c.
  virtual void gatherConcentrationGradient(size_t m) = 0;
  // A nodal sum over this rank's particles completed on the nodes shared with other ranks.
  virtual void sumOverRanks(Collective, std::vector<double>& nodal) = 0;
  // Material m's weights and nodal masses of the step.
  virtual const InterpolationWeights& weights(size_t m) const = 0;
  virtual const std::vector<double>& nodalMass(size_t m) const = 0;
};

}  // namespace anode
