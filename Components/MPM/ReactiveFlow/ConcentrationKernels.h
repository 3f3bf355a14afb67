// The diffusion subcomponent's per-particle work inside the MPM step's fused particle loops
// (docs/diffusion.md, steps 2 and 5). P2G asks addScatterTerms() once per particle for its
// lanes of the node quads (NodeQuads.h) and spread() once per node for the sums; G2P asks
// nodeValues() once per node, gather() per node a particle touches (flux and Wall only) and
// update() once per particle. The step is compiled once per kernel type, so a run without
// diffusion (NoConcentration) or without flux BCs carries none of the other cases' work.
#pragma once

#include "Components/MPM/Interpolator.h"
#include "Components/MPM/NodeQuads.h"
#include "Components/MPM/ParticleSet.h"
#include "Components/MPM/ReactiveFlow/DiffusionGridFields.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Components/MPM/ReactiveFlow/FluxRestriction.h"

namespace anode {

// The lanes ConcentrationScatter uses: of the quad it asks for after the mechanics' first
// (ScatterTerms<2>), and the kernel lane of the last quad (NodeQuads.h).
namespace ConcentrationLane {
constexpr int massConcentration = 0, fluxSource = 1, receiverWeightIn = 2, receiverWeightOut = 3;
constexpr int diffusionRate = kKernelLane;
}  // namespace ConcentrationLane

// Diffusion off: no concentration on particles or grid.
struct NoConcentration {
  static constexpr int scatterWeightQuads = 1;
  struct Particle {};
  void addScatterTerms(long, ScatterTerms<1>&) const {}
  void spread(long, const NodeQuad&, const NodeQuad&) const {}
  void nodeValues(long, double& concentration, double& rate) const { concentration = rate = 0.0; }
  void gather(Particle&, int, double) const {}
  double update(long, const Particle&, const GatheredKernelValue&, double) const { return 0.0; }
};

// P2G: (mc)_i = sum m c S (Eq. 5), R_i = -sum m grad S . q with q_p = D_p grad c_p of the
// previous step (Eqs. 6-7) and, with flux BCs, G_i = sum m rate S (Eq. 18) with, on the nodes a
// source reaches, the weights W of the particles that can receive it. Summed in the node quads
// (NodeQuads.h, ScatterTerms<2>) with the mechanics, then spread into the grid's fields.
template <bool Flux>
class ConcentrationScatter {
 public:
  static constexpr int scatterWeightQuads = 2;

  // `reached` marks the nodes a source reaches (bit 1 inflow, bit 2 outflow; flux only), cmax is
  // the material's max_concentration; `restricted`: receivers weighted by m R(c), else by m
  // (<flux_source_receivers>, docs/diffusion.md step 5); `driftDiffusivity` D0 of a flux with a
  // stress part (0: none).
  ConcentrationScatter(const ParticleSet& p, const InterpolationWeights& W,
                       const unsigned char* reached, double cmax, ConcentrationScatterFields& grid,
                       bool restricted = true, double driftDiffusivity = 0)
      : p_(p),
        d_(p),
        W_(W),
        reached_(reached),
        cmax_(cmax),
        restricted_(restricted),
        driftDiffusivity_(p.has(Physics::StressDrivenDiffusion) ? driftDiffusivity : 0.0),
        grid_(&grid) {}

  // Particle i's terms: m c, m q (q = D grad c, less D0 c (1 - c / c_max) (grad phi_0 + s_p grad
  // c_0) where the chemical potential has a stress part: ChemicalPotential.h) and, with flux, m
  // rate and m R(c) where a source can reach.
  void addScatterTerms(long i, ScatterTerms<2>& t) const {
    const double mp = p_.mass[i];
    Vec3 mq = mp * d_.diffusivity[i] * d_.concentrationGradient[i];
    if (driftDiffusivity_ > 0) {
      const double c = d_.concentration[i];
      mq -= mp * driftDiffusivity_ * c * (1 - c / cmax_) * d_.stressPotentialGradient[i];
    }
    for (int d = 0; d < 3; ++d) t.byGradient[d][ConcentrationLane::diffusionRate] = mq[d];
    double* terms = t.byWeight[1];
    terms[ConcentrationLane::massConcentration] = mp * d_.concentration[i];
    if constexpr (Flux) {
      terms[ConcentrationLane::fluxSource] = mp * d_.externalScalarFlux[i];
      // A particle's weights matter only on the nodes a source reaches (elsewhere G = 0).
      const size_t b = W_.offset[i];
      unsigned char reached = 0;
      for (int e = 0; e < W_.count[i]; ++e) reached |= reached_[W_.node[b + e]];
      const double c = d_.concentration[i] / cmax_;
      if (reached & 1)
        terms[ConcentrationLane::receiverWeightIn] =
            mp * (restricted_ ? fluxRestriction(c, true) : 1.0);
      if (reached & 2)
        terms[ConcentrationLane::receiverWeightOut] =
            mp * (restricted_ ? fluxRestriction(c, false) : 1.0);
    }
  }

  // Node k's sums from its quads into the grid's fields: the kernel's quad of weighted terms and
  // the quad of gradient terms, whose kernel lane it uses.
  void spread(long k, const NodeQuad& weighted, const NodeQuad& byGradient) const {
    const double* sums = weighted.value;
    grid_->massConcentration[k] = sums[ConcentrationLane::massConcentration];
    grid_->diffusionRate[k] = byGradient.value[ConcentrationLane::diffusionRate];
    if constexpr (Flux) {
      grid_->fluxSource[k] = sums[ConcentrationLane::fluxSource];
      grid_->receiverWeightIn[k] = sums[ConcentrationLane::receiverWeightIn];
      grid_->receiverWeightOut[k] = sums[ConcentrationLane::receiverWeightOut];
    }
  }

 private:
  const ParticleSet& p_;
  ConstDiffusionParticles d_;
  const InterpolationWeights& W_;
  const unsigned char* reached_;
  double cmax_;
  bool restricted_;
  double driftDiffusivity_;  // D0 where p.stressPotentialGradient is there, else 0
  ConcentrationScatterFields* grid_;
};

// G2P (Eq. 8): c_p += dt (sum S c-rate + s_p), s_p the flux source the particle receives,
// R(c_p) sum S G/W (docs/diffusion.md step 5), and grad c_p = sum c* grad S for the next step's
// flux. With the particle treatment of SD-Type Dirichlet (Wall), a particle touching a Dirichlet
// node takes the grid solution c_p = sum S c* instead. The sums over c* and the rate come with
// the velocity's from the node quads (NodeQuads.h); gather() adds what only flux and Wall need.
template <bool Flux, bool Wall>
class ConcentrationGather {
 public:
  struct Particle {
    double inflow = 0, outflow = 0;
    bool touchesWall = false;
  };

  // `wallMask` is 1 on the Dirichlet nodes (Wall only); cmax the material's max_concentration;
  // `restricted` as ConcentrationScatter's.
  ConcentrationGather(ParticleSet& p, const ConcentrationGridFields& g, const double* wallMask,
                      double cmax, bool restricted = true)
      : p_(p), g_(g), wallMask_(wallMask), cmax_(cmax), restricted_(restricted) {}

  // What the node's G2P quads hold of the concentration: c* and the nodal rate.
  void nodeValues(long k, double& concentration, double& rate) const {
    concentration = g_.concentrationStar[k];
    rate = g_.concentrationRate[k];
  }

  void gather(Particle& a, int k, double w) const {
    if constexpr (Flux) {
      const double source = g_.sourcePerWeight[k] * w;
      (source >= 0 ? a.inflow : a.outflow) += source;
    }
    if constexpr (Wall) a.touchesWall |= wallMask_[k] > 0;
  }

  // Updates particle i's concentration and gradient; returns the concentration change.
  double update(long i, const Particle& a, const GatheredKernelValue& sums, double dt) const {
    p_.concentrationGradient[i] = sums.gradient;
    const double c0 = p_.concentration[i];
    double received = 0;
    if (a.inflow != 0)
      received += a.inflow * (restricted_ ? fluxRestriction(c0 / cmax_, true) : 1.0);
    if (a.outflow != 0)
      received += a.outflow * (restricted_ ? fluxRestriction(c0 / cmax_, false) : 1.0);
    const double c = a.touchesWall ? sums.value : c0 + dt * (sums.rate + received);
    const double dc = c - c0;
    p_.concentration[i] = c;
    return dc;
  }

 private:
  DiffusionParticles p_;
  const ConcentrationGridFields& g_;
  const double* wallMask_;
  double cmax_;
  bool restricted_;
};

}  // namespace anode
