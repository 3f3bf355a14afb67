// Pins the P2G of the concentration alone (scatterConcentrationToNodes, ParticleLoops.h), which
// the diffusion sub-steps of a quasi-static step take after the step's full P2G: its sums of the
// diffusion kernel's terms are those the full P2G adds, bit for bit, with and without a flux.
#include <gtest/gtest.h>

#include <vector>

#include "Components/MPM/ParticleLoops.h"
#include "Components/MPM/ReactiveFlow/ConcentrationKernels.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"

namespace anode {
namespace {

// 3 x 3 x 3 cells of edge 0.5, two particles per cell and axis, linear weights, with a velocity,
// stress, c, D, gradient of c and flux source that vary from particle to particle.
struct Particles {
  Grid grid;
  ParticleSet p;
  InterpolationWeights W;
  std::vector<unsigned char> reached;

  Particles() {
    grid.lower = Vec3::Zero();
    grid.cells = Vec3i(3, 3, 3);
    grid.dx = Vec3(0.5, 0.5, 0.5);
    grid.upper = grid.lower + grid.dx.cwiseProduct(grid.cells.cast<double>());
    grid.extra = Vec3i(1, 1, 1);
    const int n = 6;
    p.resize(static_cast<size_t>(n * n * n));
    declareDiffusionArrays(p);
    p.enable(Physics::FluxBC);
    const DiffusionParticles d(p);
    W.layOut(std::vector<uint8_t>(p.count(), 8));
    for (size_t i = 0; i < p.count(); ++i) {
      const Vec3 x = (Vec3(i % n, (i / n) % n, i / (n * n)) + Vec3::Constant(0.5)) * 0.25;
      const double s = 0.1 * static_cast<double>(i % 7);
      p.mass[i] = 1 + s;
      p.volume[i] = 0.015625 * (1 + 0.5 * s);
      p.velocity[i] = Vec3(s, -2 * s, 0.5);
      p.stress[i] = Mat3::Identity() * s + Mat3::Constant(0.3);
      d.concentration[i] = 0.1 + s;
      d.diffusivity[i] = 1 + x.z();
      d.concentrationGradient[i] = Vec3(x.x() - s, 0.2, -x.y());
      d.externalScalarFlux[i] = x.z() > 1.2 ? (i % 2 ? 1e-3 : -2e-3) : 0.0;
      const size_t b = W.offset[i];
      W.count[i] =
          static_cast<uint8_t>(linearWeights(grid, x, &W.node[b], &W.weight[b], &W.gradient[b]));
    }
    // Every node a source may reach takes both kinds of receiver weight.
    reached.assign(grid.numNodes(), 3);
  }

  // The kernel's sums by the full P2G and by the P2G of the concentration alone.
  template <bool Flux>
  void scatterBoth(ConcentrationScatterFields& full, ConcentrationScatterFields& alone) const {
    constexpr int perNode = ScatterTerms<2>::quads;
    const long nodes = grid.numNodes(), n = static_cast<long>(p.count());
    for (auto* fields : {&full, &alone}) fields->resize(static_cast<int>(nodes), Flux);
    const ConcentrationScatter<Flux> intoFull(p, W, reached.data(), 1.0, full);
    const ConcentrationScatter<Flux> intoAlone(p, W, reached.data(), 1.0, alone);
    std::vector<NodeQuad> quads(perNode * nodes);
    clearQuads(quads.data(), static_cast<int>(quads.size()));
    scatterToNodes(p, W, 0, n, quads.data(), intoFull);
    for (long k = 0; k < nodes; ++k)
      intoFull.spread(k, quads[perNode * k + perNode - 2], quads[perNode * k + perNode - 1]);
    clearQuads(quads.data(), static_cast<int>(quads.size()));
    scatterConcentrationToNodes(W, 0, n, quads.data(), intoAlone);
    for (long k = 0; k < nodes; ++k)
      intoAlone.spread(k, quads[kConcentrationScatterQuads * k],
                       quads[kConcentrationScatterQuads * k + 1]);
  }
};

void expectSameSums(const std::vector<double>& full, const std::vector<double>& alone,
                    const char* what) {
  ASSERT_EQ(full.size(), alone.size()) << what;
  int nonzero = 0;
  for (size_t k = 0; k < full.size(); ++k) {
    EXPECT_EQ(full[k], alone[k]) << what << " at node " << k;
    nonzero += full[k] != 0;
  }
  EXPECT_GT(nonzero, 0) << what;  // the comparison is of sums, not of zeros
}

// Every sum the kernel spreads; the flux's are empty without one.
template <bool Flux>
void expectSameKernelSums() {
  const Particles particles;
  ConcentrationScatterFields full, alone;
  particles.scatterBoth<Flux>(full, alone);
  expectSameSums(full.massConcentration, alone.massConcentration, "sum m c S");
  expectSameSums(full.diffusionRate, alone.diffusionRate, "R");
  if (!Flux) {
    EXPECT_TRUE(alone.fluxSource.empty());
    return;
  }
  expectSameSums(full.fluxSource, alone.fluxSource, "G");
  expectSameSums(full.receiverWeightIn, alone.receiverWeightIn, "W in");
  expectSameSums(full.receiverWeightOut, alone.receiverWeightOut, "W out");
}

TEST(ParticleLoops, ConcentrationAloneAddsTheFullScattersSums) {
  expectSameKernelSums<false>();
}

TEST(ParticleLoops, ConcentrationAloneAddsTheFullScattersSumsWithAFlux) {
  expectSameKernelSums<true>();
}

}  // namespace
}  // namespace anode
