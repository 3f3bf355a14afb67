// Nodal fields of the diffusion subcomponent for one material; cleared each step, never
// reallocated. Each keeps one meaning for the whole step.
#pragma once

#include <algorithm>
#include <vector>

#include "Components/MPM/GhostNodes.h"

namespace anode {

// What P2G sums (spread from the node quads, NodeQuads.h).
struct ConcentrationScatterFields {
  std::vector<double> massConcentration;  // sum m c S (Eq. 5 numerator)
  std::vector<double> diffusionRate;      // R = -sum m (grad S . q) (Eq. 7)
  std::vector<double> fluxSource;         // G = sum m rate S (Eq. 18; flux materials only)
  // Flux materials only: W = sum m S R(c) of the particles an inflow can reach, and the same
  // with R(1 - c) for an outflow (docs/diffusion.md, step 5).
  std::vector<double> receiverWeightIn, receiverWeightOut;

  void resize(int nodes, bool flux) {
    for (auto* f : {&massConcentration, &diffusionRate}) f->assign(nodes, 0.0);
    if (flux)
      for (auto* f : {&fluxSource, &receiverWeightIn, &receiverWeightOut}) f->assign(nodes, 0.0);
  }
  // Zeroes every field on nodes [begin, end).
  void clear(long begin, long end) {
    for (auto* f :
         {&massConcentration, &diffusionRate, &fluxSource, &receiverWeightIn, &receiverWeightOut})
      if (!f->empty()) std::fill(f->begin() + begin, f->begin() + end, 0.0);
  }
  // Adds the fields laid out to `arrays`, for the ranks to complete their sums on the nodes they
  // share (GhostNodes::sumOverRanks).
  void addScatteredArrays(std::vector<NodeArray>& arrays) {
    for (std::vector<double>* f :
         {&massConcentration, &diffusionRate, &fluxSource, &receiverWeightIn, &receiverWeightOut})
      if (!f->empty()) arrays.push_back({f->data(), 1});
  }
};

struct ConcentrationGridFields : ConcentrationScatterFields {
  std::vector<double> concentrationNoBC;  // c = sum m c S / m (Eq. 5)
  std::vector<double> concentration;      // g.concentration: the same after the SD-Type BCs
  std::vector<double> concentrationStar;  // c* = c + (R + G)/m dt (Eq. 18; without G under
                                          // <flux_source_in_cstar>false), then the SD-Type BCs
  std::vector<double> concentrationRate;  // g.concentrationRate: (c° - c_noBC)/dt, drives Eq. 8
  // Flux materials only.
  std::vector<double> concentrationNoSource;  // c° = c + R/m dt under the SD-Type BCs
  std::vector<double> sourcePerWeight;  // G / W: what a receiving particle gets per m S R (per
                                        // m S under <flux_source_receivers>weights)
  std::vector<unsigned char>
      sourceReached;  // bit 1 (2): an inflow (outflow) source reaches the node

  void resize(int nodes, bool flux) {
    ConcentrationScatterFields::resize(nodes, flux);
    for (auto* f : {&concentrationNoBC, &concentration, &concentrationStar, &concentrationRate})
      f->assign(nodes, 0.0);
    if (!flux) return;
    for (auto* f : {&concentrationNoSource, &sourcePerWeight}) f->assign(nodes, 0.0);
    sourceReached.assign(nodes, 0);
  }
  // Zeroes every field but sourceReached on nodes [begin, end).
  void clearAll(long begin, long end) {
    clear(begin, end);
    for (auto* f : {&concentrationNoBC, &concentration, &concentrationStar, &concentrationRate,
                    &concentrationNoSource, &sourcePerWeight})
      if (!f->empty()) std::fill(f->begin() + begin, f->begin() + end, 0.0);
  }
};

}  // namespace anode
