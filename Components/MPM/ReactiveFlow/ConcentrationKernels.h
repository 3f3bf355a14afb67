// The diffusion subcomponent's per-particle work inside the MPM step's fused particle loops
// (docs/diffusion.md, steps 2 and 5): the P2G scatter calls particle() once per particle and
// scatter() per node it touches; the G2P gather calls gather() per node and update() once. The
// step is compiled once per kernel type, so a run without diffusion (NoConcentration) or without
// flux BCs carries none of the other cases' work.
#pragma once

#include <vector>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/ParticleSet.h"
#include "Components/MPM/ReactiveFlow/DiffusionGridFields.h"
#include "Components/MPM/ReactiveFlow/FluxRestriction.h"

namespace anode {

// Diffusion off: no concentration on particles or grid.
struct NoConcentration {
  struct Particle {};
  Particle particle(long) const { return {}; }
  void scatter(const Particle&, int, double, const Vec3&) const {}
  NoConcentration forThread(int, const std::vector<NodeRange>&) const { return {}; }
  void addThreadBuffers(long, const std::vector<NodeRange>&) const {}
  void gather(Particle&, int, double, const Vec3&) const {}
  double update(long, const Particle&, double) const { return 0.0; }
};

// The nodal accumulators one P2G scatter writes into (the grid's own, or a thread's buffer), as
// plain pointers so the scatter loop keeps them in registers.
struct ConcentrationScatterTarget {
  double* massConcentration;
  double* diffusionRate;
  double* fluxSource;
  double* receiverWeightIn;
  double* receiverWeightOut;

  static ConcentrationScatterTarget of(ConcentrationScatterFields& f) {
    return {f.massConcentration.data(), f.diffusionRate.data(), f.fluxSource.data(),
            f.receiverWeightIn.data(), f.receiverWeightOut.data()};
  }
};

// P2G: (mc)_i = sum m c S (Eq. 5), R_i = -sum m grad S . q with q_p = D_p grad c_p of the
// previous step (Eqs. 6-7) and, with flux BCs, G_i = sum m rate S (Eq. 18) with, on the nodes a
// source reaches, the weights W of the particles that can receive it.
template <bool Flux>
class ConcentrationScatter {
 public:
  struct Particle {
    double mc, mrate, mIn, mOut;
    Vec3 mq;
  };

  // `reached` marks the nodes a source reaches (bit 1 inflow, bit 2 outflow; flux only), cmax is
  // the material's max_concentration; `threadBuffers` are the per-thread scatter targets.
  ConcentrationScatter(const ParticleSet& p, const InterpolationWeights& W,
                       const unsigned char* reached, double cmax, ConcentrationScatterFields& grid,
                       std::vector<ConcentrationScatterFields>& threadBuffers)
      : p_(p),
        W_(W),
        reached_(reached),
        cmax_(cmax),
        grid_(&grid),
        buffers_(&threadBuffers),
        target_(ConcentrationScatterTarget::of(grid)) {}

  Particle particle(long i) const {
    const double mp = p_.mass[i];
    Particle d{mp * p_.concentration[i], 0, 0, 0,
               mp * p_.diffusivity[i] * p_.concentrationGradient[i]};
    if constexpr (Flux) {
      d.mrate = mp * p_.externalScalarFlux[i];
      // A particle's weights matter only on the nodes a source reaches (elsewhere G = 0).
      const size_t b = W_.offset[i];
      unsigned char reached = 0;
      for (int e = 0; e < W_.count[i]; ++e) reached |= reached_[W_.node[b + e]];
      const double c = p_.concentration[i] / cmax_;
      if (reached & 1) d.mIn = mp * fluxRestriction(c, true);
      if (reached & 2) d.mOut = mp * fluxRestriction(c, false);
    }
    return d;
  }

  void scatter(const Particle& d, int n, double w, const Vec3& grad) const {
    target_.massConcentration[n] += d.mc * w;
    target_.diffusionRate[n] -= grad.dot(d.mq);
    if constexpr (Flux) {
      target_.fluxSource[n] += d.mrate * w;
      target_.receiverWeightIn[n] += d.mIn * w;
      target_.receiverWeightOut[n] += d.mOut * w;
    }
  }

  // The kernel scattering into the buffer of thread t >= 1 (the first thread scatters into the
  // grid), cleared on the nodes of `cleared` (those t's particles can touch).
  ConcentrationScatter forThread(int t, const std::vector<NodeRange>& cleared) const {
    ConcentrationScatter k = *this;
    ConcentrationScatterFields& buffer = (*buffers_)[t - 1];
    for (const NodeRange& r : cleared) buffer.clear(r.begin, r.end);
    k.target_ = ConcentrationScatterTarget::of(buffer);
    return k;
  }

  // Adds the buffers of threads 1, 2, ... that touch node k to the grid there, in thread order
  // (deterministic).
  void addThreadBuffers(long k, const std::vector<NodeRange>& touched) const {
    for (size_t u = 1; u < touched.size(); ++u) {
      if (!touched[u].contains(k)) continue;
      const ConcentrationScatterFields& b = (*buffers_)[u - 1];
      grid_->massConcentration[k] += b.massConcentration[k];
      grid_->diffusionRate[k] += b.diffusionRate[k];
      if constexpr (Flux) {
        grid_->fluxSource[k] += b.fluxSource[k];
        grid_->receiverWeightIn[k] += b.receiverWeightIn[k];
        grid_->receiverWeightOut[k] += b.receiverWeightOut[k];
      }
    }
  }

 private:
  const ParticleSet& p_;
  const InterpolationWeights& W_;
  const unsigned char* reached_;
  double cmax_;
  ConcentrationScatterFields* grid_;
  std::vector<ConcentrationScatterFields>* buffers_;
  ConcentrationScatterTarget target_;
};

// G2P (Eq. 8): c_p += dt (sum S c-rate + s_p), s_p the flux source the particle receives,
// R(c_p) sum S G/W (docs/diffusion.md step 5), and grad c_p = sum c* grad S for the next step's
// flux. With the particle treatment of SD-Type Dirichlet (Wall), a particle touching a Dirichlet
// node takes the grid solution c_p = sum S c* instead.
template <bool Flux, bool Wall>
class ConcentrationGather {
 public:
  struct Particle {
    Vec3 gradC = Vec3::Zero();
    double cRate = 0, cGrid = 0, inflow = 0, outflow = 0;
    bool touchesWall = false;
  };

  // `wallMask` is 1 on the Dirichlet nodes (Wall only); cmax the material's max_concentration.
  ConcentrationGather(ParticleSet& p, const ConcentrationGridFields& g, const double* wallMask,
                      double cmax)
      : p_(p), g_(g), wallMask_(wallMask), cmax_(cmax) {}

  void gather(Particle& a, int k, double w, const Vec3& grad) const {
    a.gradC += g_.concentrationStar[k] * grad;
    a.cRate += g_.concentrationRate[k] * w;
    if constexpr (Flux) {
      const double source = g_.sourcePerWeight[k] * w;
      (source >= 0 ? a.inflow : a.outflow) += source;
    }
    if constexpr (Wall) {
      a.cGrid += g_.concentrationStar[k] * w;
      a.touchesWall |= wallMask_[k] > 0;
    }
  }

  // Updates particle i's concentration and gradient; returns the concentration change.
  double update(long i, const Particle& a, double dt) const {
    p_.concentrationGradient[i] = a.gradC;
    const double c0 = p_.concentration[i];
    double received = 0;
    if (a.inflow != 0) received += a.inflow * fluxRestriction(c0 / cmax_, true);
    if (a.outflow != 0) received += a.outflow * fluxRestriction(c0 / cmax_, false);
    const double c = a.touchesWall ? a.cGrid : c0 + dt * (a.cRate + received);
    const double dc = c - c0;
    p_.concentration[i] = c;
    return dc;
  }

 private:
  ParticleSet& p_;
  const ConcentrationGridFields& g_;
  const double* wallMask_;
  double cmax_;
};

}  // namespace anode
