// Pins particles moving between ranks (Components/MPM/ParticleMigration.h): every array a
// material has travels with its particle, through ParticleSet's one list of arrays; the
// particles that stay keep their order; an empty batch is a count of zero.
#include <gtest/gtest.h>

#include "Components/MPM/ParticleMigration.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"

namespace anode {
namespace {

// Five particles with mechanics, diffusion, splitting and constitutive-model arrays, each value
// telling its particle.
ParticleSet numberedParticles() {
  ParticleSet p;
  p.resize(5);
  declareDiffusionArrays(p);
  p.enable(Physics::Splitting);
  p.declareModelArray(ParticleField<double>{nullptr, Physics::Plasticity, 0.0, OnSplit::Copy});
  for (size_t i = 0; i < 5; ++i) {
    p.id[i] = 10 + static_cast<int64_t>(i);
    p.x[i] = Vec3(i, 2.0 * i, 3.0 * i);
    p.mass[i] = 1.0 + i;
    p.F[i] = (1.0 + i) * Mat3::Identity();
    diffusionParticles(p).concentration[i] = 0.1 * i;
    diffusionParticles(p).concentrationGradient[i] = Vec3::Constant(-1.0 * i);
    p.refined[i] = static_cast<uint8_t>(i % 2);
    p.modelArray<double>(0)[i] = 0.5 * i;
  }
  return p;
}

void expectSameParticle(const ParticleSet& a, size_t i, const ParticleSet& b, size_t j) {
  EXPECT_EQ(a.modelArray<double>(0)[i], b.modelArray<double>(0)[j]);
  EXPECT_EQ(a.id[i], b.id[j]);
  EXPECT_EQ(a.x[i], b.x[j]);
  EXPECT_EQ(a.mass[i], b.mass[j]);
  EXPECT_EQ(a.F[i], b.F[j]);
  EXPECT_EQ(diffusionParticles(a).concentration[i], diffusionParticles(b).concentration[j]);
  EXPECT_EQ(diffusionParticles(a).concentrationGradient[i],
            diffusionParticles(b).concentrationGradient[j]);
  EXPECT_EQ(a.refined[i], b.refined[j]);
}

TEST(ParticleMigration, PackedParticlesArriveWithEveryArray) {
  const ParticleSet from = numberedParticles();
  std::string message;
  packParticles(from, {1, 3}, message);
  packParticles(from, {}, message);  // a second material with nothing to send
  ParticleSet to = numberedParticles();
  ParticleSet none = numberedParticles();
  keepParticles(none, {});
  const char* in = message.data();
  unpackParticles(in, to);
  unpackParticles(in, none);
  EXPECT_EQ(in, message.data() + message.size());
  ASSERT_EQ(to.count(), 7u);
  expectSameParticle(from, 1, to, 5);
  expectSameParticle(from, 3, to, 6);
  EXPECT_EQ(none.count(), 0u);
  // Arrays of physics the material lacks stay empty.
  EXPECT_EQ(diffusionParticles(to).externalScalarFlux.size(), 0u);
}

TEST(ParticleMigration, KeptParticlesKeepTheirOrder) {
  const ParticleSet before = numberedParticles();
  ParticleSet p = before;
  keepParticles(p, {0, 2, 4});
  ASSERT_EQ(p.count(), 3u);
  expectSameParticle(before, 0, p, 0);
  expectSameParticle(before, 2, p, 1);
  expectSameParticle(before, 4, p, 2);
  ParticleSet all = before;
  keepParticles(all, {0, 1, 2, 3, 4});
  ASSERT_EQ(all.count(), 5u);
  for (size_t i = 0; i < 5; ++i) expectSameParticle(before, i, all, i);
}

TEST(ParticleMigration, ReorderedParticlesCarryEveryArray) {
  const ParticleSet before = numberedParticles();
  ParticleSet p = before;
  reorderParticles(p, {4, 0, 3, 1, 2});
  ASSERT_EQ(p.count(), 5u);
  expectSameParticle(before, 4, p, 0);
  expectSameParticle(before, 0, p, 1);
  expectSameParticle(before, 2, p, 4);
}

}  // namespace
}  // namespace anode
