// The global quantities of the state after a step (history.csv, the progress line).
#pragma once

#include <cstddef>
#include <vector>

namespace anode {

struct StepSummary {
  double kineticEnergy = 0;
  // Sum over particles of volume x ConstitutiveModel::elasticEnergyDensity(stress).
  double elasticEnergy = 0;
  double minJ = 1, maxJ = 1;
  size_t particles = 0;
  bool diffusion = false;
  double totalLithium = 0;  // sum m c over all materials
  // Over the materials whose c can change (of every material when none can): sum m c and
  // sum m c_max, whose ratio is the state of charge.
  double chargeableLithium = 0, lithiumCapacity = 0;
  double minConcentration = 0, maxConcentration = 0;
  // Per material whose c can change, in material order, when two or more can (history.csv's
  // per-material columns): the material's index, its sum m c and its range of c.
  struct MaterialLithium {
    size_t material = 0;
    double lithium = 0, minConcentration, maxConcentration;
  };
  std::vector<MaterialLithium> perMaterial;
};

}  // namespace anode
