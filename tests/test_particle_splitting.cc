// Pins particle splitting (Components/MPM/ParticleSplitting.h, UINTAH_UPS.md §9): which edge a
// stretched domain splits along, and a split into four that conserves mass, volume, momentum and
// lithium, places the children along the edge and numbers them; the flux faces shared on the
// diffusion side (ExternalScalarFlux::shareFacesOnSplit).
#include <gtest/gtest.h>
#include <omp.h>

#include "Components/MPM/ParticleSplitting.h"
#include "Components/MPM/ReactiveFlow/ExternalScalarFlux.h"

namespace anode {
namespace {

std::vector<long> parentsOf(const std::vector<SplitParticle>& splits) {
  std::vector<long> parents;
  for (const SplitParticle& s : splits) parents.push_back(static_cast<long>(s.child[0]));
  return parents;
}

TEST(ParticleSplitting, SplitAxisComparesSquaredEdgeLengths) {
  const auto domain = [](double a, double b, double c) {
    return Vec3(a, b, c).asDiagonal().toDenseMatrix();
  };
  EXPECT_EQ(splitAxis(domain(1, 1, 1), 2.0, 3), -1);
  EXPECT_EQ(splitAxis(domain(1.9, 1, 1), 2.0, 3), -1);  // 1.9^2 < 4 x 1^2
  EXPECT_EQ(splitAxis(domain(2.1, 1, 1), 2.0, 3), 0);
  EXPECT_EQ(splitAxis(domain(1, 2.1, 1), 2.0, 3), 1);
  EXPECT_EQ(splitAxis(domain(1, 1, 2.1), 2.0, 3), 2);
  EXPECT_EQ(splitAxis(domain(1, 1, 2.1), 2.0, 2), -1);  // the third edge only in 3-D
  // A sheared domain: the edge's length, not its x extent, counts.
  Mat3 sheared = Mat3::Identity();
  sheared(1, 0) = 2.0;  // first edge (1, 2, 0): length^2 5 > 4
  EXPECT_EQ(splitAxis(sheared, 2.0, 3), 0);
}

// One particle stretched 3-fold along x (domain 1.5 x 0.5 x 0.5 with dx = 1), with diffusion,
// flux and splitting arrays.
ParticleSet stretchedParticle() {
  ParticleSet p;
  p.resize(1);
  declareDiffusionArrays(p);
  p.enable(Physics::FluxBC);
  p.enable(Physics::Splitting);
  p.id[0] = 7;
  p.x[0] = Vec3(2, 2, 2);
  p.velocity[0] = Vec3(1, -2, 0.5);
  p.mass[0] = 8;
  p.volume[0] = 0.375;
  p.F[0] = Vec3(3, 1, 1).asDiagonal();
  p.size[0] = Vec3(0.5, 0.5, 0.5).asDiagonal();
  diffusionParticles(p).concentration[0] = 0.4;
  return p;
}

Grid unitGrid() {
  Grid g;
  g.cells = Vec3i(4, 4, 4);
  g.upper = Vec3(4, 4, 4);
  return g;
}

TEST(ParticleSplitting, FourChildrenConserveMassMomentumAndLithium) {
  ParticleSet p = stretchedParticle();
  int64_t nextId = 100;
  ASSERT_EQ(parentsOf(splitStretchedParticles(p, unitGrid(), 2.0, nextId)), std::vector<long>{0});
  ASSERT_EQ(p.count(), 4u);
  EXPECT_EQ(nextId, 103);
  double mass = 0, volume = 0, lithium = 0;
  Vec3 momentum = Vec3::Zero();
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(p.mass[i], 2.0);
    EXPECT_EQ(p.volume[i], 0.375 / 4);
    EXPECT_EQ(p.refined[i], 1);
    EXPECT_EQ(p.F[i], Mat3(Vec3(3, 1, 1).asDiagonal()));
    // The split edge of the reference domain is quartered: each child's domain is 0.375 long.
    EXPECT_EQ(p.size[i], Mat3(Vec3(0.125, 0.5, 0.5).asDiagonal()));
    mass += p.mass[i];
    volume += p.volume[i];
    lithium += p.mass[i] * diffusionParticles(p).concentration[i];
    momentum += p.mass[i] * p.velocity[i];
  }
  EXPECT_EQ(mass, 8.0);
  EXPECT_EQ(volume, 0.375);
  EXPECT_EQ(lithium, 8 * 0.4);
  EXPECT_EQ(momentum, Vec3(8, -16, 4));
  // The parent becomes the first child; children at -3/8, -1/8, 1/8, 3/8 of the edge (1.5, 0, 0).
  EXPECT_EQ(p.id[0], 7);
  EXPECT_EQ(p.id[1], 100);
  EXPECT_EQ(p.id[3], 102);
  const double offsets[4] = {-0.5625, -0.1875, 0.1875, 0.5625};
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(p.x[i], Vec3(2 + offsets[i], 2, 2));
  // Refined particles do not split again.
  p.F[0] = Vec3(9, 1, 1).asDiagonal();
  EXPECT_TRUE(splitStretchedParticles(p, unitGrid(), 2.0, nextId).empty());
}

TEST(ParticleSplitting, ListsTheParentsInIndexOrderWithTheirChildrenAppendedSo) {
  // Nine particles, the stretched ones at 1, 4, 5 and 8, searched by 1 to 3 threads (each thread
  // a block of indices): the same parents in index order, each one's 3 children in that order.
  const int threadsBefore = omp_get_max_threads();
  for (int threads = 1; threads <= 3; ++threads) {
    ParticleSet p;
    p.resize(9);
    p.enable(Physics::Splitting);
    for (size_t i = 0; i < 9; ++i) {
      p.id[i] = static_cast<int64_t>(i);
      p.x[i] = Vec3(2, 2, 2);
      p.velocity[i] = Vec3(static_cast<double>(i), 0, 0);
      p.size[i] = Vec3(0.5, 0.5, 0.5).asDiagonal();
      p.F[i] = i == 1 || i == 4 || i == 5 || i == 8 ? Mat3(Vec3(3, 1, 1).asDiagonal())
                                                    : Mat3::Identity();
    }
    omp_set_num_threads(threads);
    int64_t nextId = 100;
    EXPECT_EQ(parentsOf(splitStretchedParticles(p, unitGrid(), 2.0, nextId)),
              (std::vector<long>{1, 4, 5, 8}))
        << threads << " thread(s)";
    EXPECT_EQ(p.count(), 21u);
    const double parents[4] = {1, 4, 5, 8};
    for (size_t c = 0; c < 12 && 9 + c < p.count(); ++c) {
      EXPECT_EQ(p.id[9 + c], static_cast<int64_t>(100 + c));
      EXPECT_EQ(p.velocity[9 + c].x(), parents[c / 3]) << "child " << c;
    }
  }
  omp_set_num_threads(threadsBefore);
}

TEST(ParticleSplitting, FluxFacesGoWholeToTheNearestChildOrAreShared) {
  // The particle carries the x+ face of a box BC (normal along the split: the nearest child
  // takes all of it) and the y+ face of another (normal across the split: each child a quarter).
  ParticleSet p = stretchedParticle();
  ScalarFluxBC xFace, yFace;
  xFace.boxMin = Vec3(2.75, 0, 0), xFace.boxMax = Vec3(2.75, 4, 4);
  yFace.boxMin = Vec3(0, 2.25, 0), yFace.boxMax = Vec3(4, 2.25, 4);
  diffusionParticles(p).loadCurveID[0] = Vec3i(1, 2, 0);
  diffusionParticles(p).area[0] = Vec3(0.25, 0.75, 0);
  int64_t nextId = 100;
  const std::vector<SplitParticle> splits = splitStretchedParticles(p, unitGrid(), 2.0, nextId);
  ASSERT_EQ(parentsOf(splits), std::vector<long>{0});
  ExternalScalarFlux({xFace, yFace}).shareFacesOnSplit(p, splits);
  double xArea = 0, yArea = 0;
  for (size_t i = 0; i < 4; ++i)
    for (int s = 0; s < 3; ++s) {
      if (diffusionParticles(p).loadCurveID[i][s] == 1) xArea += diffusionParticles(p).area[i][s];
      if (diffusionParticles(p).loadCurveID[i][s] == 2) {
        EXPECT_EQ(diffusionParticles(p).area[i][s], 0.75 / 4);
        yArea += diffusionParticles(p).area[i][s];
      }
    }
  EXPECT_EQ(xArea, 0.25);
  EXPECT_EQ(yArea, 0.75);
  // The x face went to the child at x = 2.5625, nearest the face at 2.75.
  EXPECT_EQ(diffusionParticles(p).loadCurveID[3][0], 1);
  EXPECT_EQ(diffusionParticles(p).area[3][0], 0.25);
  for (size_t i = 0; i < 3; ++i) EXPECT_NE(diffusionParticles(p).loadCurveID[i][0], 1);
}

}  // namespace
}  // namespace anode
