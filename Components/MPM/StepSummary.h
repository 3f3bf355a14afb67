// The global quantities of the state after a step (history.csv, the progress line).
#pragma once

#include <cstddef>
#include <utility>
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
  // Per material, in material order (history.csv's stress columns): its volume, the volume
  // integral of its Cauchy stress (xx, yy, zz, yz, xz, xy) and of the von Mises stress, and for
  // a material that yields the plastic work rate sum V sigma_e dep/dt (the equivalent stress
  // times the step's equivalent plastic strain rate: sigma : D^p of the radial return).
  struct MaterialStress {
    double volume = 0;
    double stressIntegral[6] = {0, 0, 0, 0, 0, 0};
    double vonMisesIntegral = 0;
    bool yields = false;
    double plasticWorkRate = 0;
  };
  std::vector<MaterialStress> stress;
  // Per <scalar_flux> with a <surface_reaction>, in file order: its number (1-based) and the
  // electrode's potential (V) at the state's flux rates.
  std::vector<std::pair<int, double>> electrodePotentials;
};

}  // namespace anode
