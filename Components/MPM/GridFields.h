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
  std::vector<unsigned char> sourceReached;  // 1 on the nodes of particles with a flux rate
  std::vector<double> concentrationStar;   // c + dc/dt dt, then BCs
  std::vector<double> concentrationRate;   // g.concentrationRate: drives the particles (Eq. 8)

  void resizeDiffusion(int nodes, bool flux) {
    for (auto* f : {&concentration, &concentrationNoBC, &diffusionRate, &externalScalarFlux,
                    &concentrationStar, &concentrationRate})
      f->assign(nodes, 0.0);
    if (flux) {
      for (auto* f : {&receiverWeightIn, &receiverWeightOut}) f->assign(nodes, 0.0);
      sourceReached.assign(nodes, 0);
    }
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
