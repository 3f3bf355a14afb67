// What every verification result (VibratingBar.h, FluxSlab.h, DiffusionSlab1D.h) reports besides
// its errors: the case, its size and its cost.
#pragma once

#include <cstddef>
#include <string>

namespace anode {

struct RunSummary {
  std::string interpolator;
  int cells = 0;
  size_t particles = 0;
  long steps = 0;
  double wallSeconds = 0;  // building the Simulation, stepping and measuring
  double finalTime = 0;
};

}  // namespace anode
