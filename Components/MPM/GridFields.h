// Nodal fields of one material on the background grid; cleared each step, never reallocated.
#pragma once

#include <vector>

#include "Core/Math/Types.h"

namespace anode {

struct GridFields {
  std::vector<double> mass;          // g.mass (Eq. 4)
  std::vector<Vec3> velocity;        // g.velocity: momentum during P2G, then velocity
  std::vector<Vec3> internalForce;   // g.internalforce
  std::vector<Vec3> velocityStar;    // g.velocity_star: after integration and BCs
  std::vector<Vec3> acceleration;    // g.acceleration
  // Diffusion (only with <do_scalar_diffusion>true).
  std::vector<double> concentration;       // g.concentration: sum m c S / m (Eq. 5), then BCs
  std::vector<double> concentrationNoBC;   // the same before the SD-Type BCs
  std::vector<double> diffusionRate;       // -sum m (grad S . q) during P2G (Eq. 7 numerator)
  std::vector<double> externalScalarFlux;  // sum m rate S (Eq. 18 numerator), then G / W
  std::vector<double> receiverWeightIn;    // W = sum m S R(c) of the particles an inflow can reach
  std::vector<double> receiverWeightOut;   // the same with R(1 - c), for an outflow
  std::vector<unsigned char> sourceReached;  // bit 1 (2): an inflow (outflow) source reaches the node
  std::vector<double> concentrationStar;   // c + dc/dt dt, then BCs
  std::vector<double> concentrationRate;   // g.concentrationRate: drives the particles (Eq. 8)

  // The diffusion fields a P2G scatter accumulates (all a thread's private buffer needs).
  void resizeDiffusionScatter(int nodes) {
    for (auto* f : {&concentration, &diffusionRate, &externalScalarFlux}) f->assign(nodes, 0.0);
  }
  void resizeFluxScatter(int nodes) {
    for (auto* f : {&receiverWeightIn, &receiverWeightOut}) f->assign(nodes, 0.0);
  }

  void resizeDiffusion(int nodes) {
    resizeDiffusionScatter(nodes);
    for (auto* f : {&concentrationNoBC, &concentrationStar, &concentrationRate}) f->assign(nodes, 0.0);
  }
  // Only for a material whose particles receive a flux BC.
  void resizeFlux(int nodes) {
    resizeFluxScatter(nodes);
    sourceReached.assign(nodes, 0);
  }

  void resize(int nodes) {
    mass.assign(nodes, 0.0);
    velocity.assign(nodes, Vec3::Zero());
    internalForce.assign(nodes, Vec3::Zero());
    velocityStar.assign(nodes, Vec3::Zero());
    acceleration.assign(nodes, Vec3::Zero());
  }
};

}  // namespace anode
