// The step's two fused particle loops (ExplicitStep::advance's tasks 2 and 7-8): the P2G scatter
// and the G2P update with the stress update. Each is compiled per diffusion kernel (ReactiveFlow's
// ConcentrationKernels.h; NoConcentration without diffusion) and the G2P loop per constitutive
// model type, so a loop carries only the work its material needs and calls nothing virtual.
#pragma once

#include <algorithm>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/NodeGather.h"
#include "Components/MPM/NodeQuads.h"
#include "Components/MPM/ParticleSet.h"
#include "Components/MPM/StressLanes.h"
#include "Core/Math/Simd.h"

namespace anode {

// P2G of particles [begin, end) into node quads (NodeQuads.h, ScatterTerms), ScatterTerms<
// Concentration::scatterWeightQuads>::quads per node: mass (Eq. 4), momentum, internal force
// f = -sum V sigma grad S, and the concentration kernel's sums.
template <class Concentration>
void scatterToNodes(const ParticleSet& p, const InterpolationWeights& W, long begin, long end,
                    NodeQuad* quads, const Concentration& concentration) {
  using Terms = ScatterTerms<Concentration::scatterWeightQuads>;
  constexpr int weighted = Concentration::scatterWeightQuads, perNode = Terms::quads;
  for (long i = begin; i < end; ++i) {
    Terms t;
    const double mp = p.mass[i];
    const Vec3 mv = mp * p.velocity[i];
    const Mat3 Vsigma = p.volume[i] * p.stress[i];
    t.byWeight[0][ScatterLane::mass] = mp;
    for (int a = 0; a < 3; ++a) {
      t.byWeight[0][ScatterLane::momentum + a] = mv[a];
      for (int d = 0; d < 3; ++d) t.byGradient[d][ScatterLane::internalForce + a] = Vsigma(a, d);
    }
    concentration.addScatterTerms(i, t);
    Quad byWeight[weighted], byGradient[3];
    for (int s = 0; s < weighted; ++s) byWeight[s].copy_from(t.byWeight[s], stdx::vector_aligned);
    for (int d = 0; d < 3; ++d) byGradient[d].copy_from(t.byGradient[d], stdx::vector_aligned);
    const size_t b = W.offset[i];
    for (int e = 0; e < W.count[i]; ++e) {
      NodeQuad* node = quads + static_cast<size_t>(W.node[b + e]) * perNode;
      const double w = W.weight[b + e];
      const Vec3& grad = W.gradient[b + e];
      for (int s = 0; s < weighted; ++s) store(load(node[s]) + byWeight[s] * w, node[s]);
      store(load(node[weighted]) -
                (byGradient[0] * grad[0] + byGradient[1] * grad[1] + byGradient[2] * grad[2]),
            node[weighted]);
    }
  }
}

// P2G of the concentration kernel's sums alone, kConcentrationScatterQuads per node (NodeQuads.h):
// for particles that changed nothing but their concentration since the last full P2G.
template <class Concentration>
void scatterConcentrationToNodes(const InterpolationWeights& W, long begin, long end,
                                 NodeQuad* quads, const Concentration& concentration) {
  constexpr int weighted = Concentration::scatterWeightQuads;
  if constexpr (weighted > 1) {  // a kernel with quads of its own
    for (long i = begin; i < end; ++i) {
      ScatterTerms<weighted> t;
      concentration.addScatterTerms(i, t);
      Quad byWeight, byGradient[3];
      byWeight.copy_from(t.byWeight[weighted - 1], stdx::vector_aligned);
      for (int d = 0; d < 3; ++d) byGradient[d].copy_from(t.byGradient[d], stdx::vector_aligned);
      const size_t b = W.offset[i];
      for (int e = 0; e < W.count[i]; ++e) {
        NodeQuad* node = quads + static_cast<size_t>(W.node[b + e]) * kConcentrationScatterQuads;
        const Vec3& grad = W.gradient[b + e];
        store(load(node[0]) + byWeight * W.weight[b + e], node[0]);
        store(load(node[1]) -
                  (byGradient[0] * grad[0] + byGradient[1] * grad[1] + byGradient[2] * grad[2]),
              node[1]);
      }
    }
  }
}

// Writes the node quads G2P reads (NodeQuads.h) on the nodes of `nodes`, from the grid's
// velocity_star and acceleration and the concentration kernel's nodal values.
template <class Concentration>
void fillGatherQuads(const GridFields& g, const Concentration& concentration,
                     const std::vector<NodeRange>& nodes, NodeQuad* quads) {
  forEachNode(nodes, [&](long k) {
    double* v = quads[kGatherQuads * k].value;
    double* a = quads[kGatherQuads * k + 1].value;
    for (int d = 0; d < 3; ++d) {
      v[d] = g.velocityStar[k][d];
      a[d] = g.acceleration[k][d];
    }
    concentration.nodeValues(k, v[kKernelLane], a[kKernelLane]);
  });
}

// What the G2P update of one material needs besides its particles and kernels.
struct ParticleUpdate {
  const NodeQuad* quads;  // fillGatherQuads on the nodes the particles reach
  const InterpolationWeights& W;
  double density;  // rho0: V = m / rho0 J
  int minimumSubcyclesForF;
  bool swells;  // the stress sees the concentration change
  double dt;
};

// The stress update's inputs for one block of particles (StressLanes.h) with the velocity
// gradient L; a lane's results are written back to its particle only where `update` is set.
template <class Model>
struct StressBlock : StressLanes<Model> {
  Mat3Pack L;
  bool update[Pack::size()];

  void setPlaceholder(int l) {
    StressLanes<Model>::setPlaceholder(l);
    setLane(L, l, Mat3::Zero());
    update[l] = false;
  }
};

// G2P and the stress update of particles [0, n) (Eqs. 8, 25-39): velocity, position and F from
// the grid, volume, the concentration kernel's update, then the model's stress and its own
// state (Model::StateArrays, ConcreteModels.h), one block of
// Pack::size() particles at a time. Returns the first particle whose det F is not positive (n if
// none); its stress is not updated.
template <class Model, class Concentration>
long updateParticles(ParticleSet& p, const ParticleUpdate& u, const Model& model,
                     const Concentration& concentration) {
  const InterpolationWeights& W = u.W;
  const auto state = model.stateArrays(p);
  const double dt = u.dt;
  const long n = static_cast<long>(p.count());
  constexpr int lanes = static_cast<int>(Pack::size());
  const long blocks = (n + lanes - 1) / lanes;
  long firstInverted = n;
#pragma omp parallel for schedule(static) reduction(min : firstInverted)
  for (long block = 0; block < blocks; ++block) {
    StressBlock<Model> s;
    for (int l = 0; l < lanes; ++l) {
      const long i = block * lanes + l;
      if (i >= n) {
        s.setPlaceholder(l);
        continue;
      }
      typename Concentration::Particle c{};
      const GatheredQuads sums = gatherFromNodes(W, i, u.quads, concentration, c);
      const Vec3 vel(sums.velocity[0], sums.velocity[1], sums.velocity[2]);
      const Vec3 acc(sums.acceleration[0], sums.acceleration[1], sums.acceleration[2]);
      Mat3 gradV;
      for (int a = 0; a < 3; ++a) {
        gradV(a, 0) = sums.byX[a];
        gradV(a, 1) = sums.byY[a];
        gradV(a, 2) = sums.byZ[a];
      }
      // F^{n+1} = (I + L dt/N)^N F^n, subcycled when L dt is large (Uintah's rule).
      const int cycles = std::min(
          std::max(u.minimumSubcyclesForF, 2 * static_cast<int>(gradV.norm() * dt)), 10000);
      const Mat3 increment = Mat3::Identity() + gradV * (dt / cycles);
      Mat3 F = p.F[i];
      for (int step = 0; step < cycles; ++step) F = increment * F;
      const double J = F.determinant();
      p.velocity[i] += acc * dt;
      moveParticle(p, i, vel * dt, F, J, u.density);
      const double dc = concentration.update(i, c, sums.kernelValue(), dt);
      if (!(J > 0)) {  // no stress update for an inverted particle: the caller stops the run
        firstInverted = std::min(firstInverted, i);
        s.setPlaceholder(l);
        continue;
      }
      s.setParticle(l, p, i, F, u.swells ? dc : 0.0, state);
      setLane(s.L, l, gradV);
      s.update[l] = true;
    }
    const Mat3Pack stress = model.updateStress(s.stress, s.F, s.L, s.dc, dt, s.state);
    for (int l = 0; l < lanes; ++l) {
      if (!s.update[l]) continue;
      const long i = block * lanes + l;
      storeStress<Model>(p, i, state, stress, s.state, l);
    }
  }
  return firstInverted;
}

}  // namespace anode
