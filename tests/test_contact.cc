// Pins contact on the grid (Components/MPM/Contact/Contact.h, UINTAH_UPS.md §10): null leaves the
// materials alone, single_velocity gives every member the centre-of-mass velocity at nodes they
// share and conserves momentum there; <contact> reading and its checks.
#include <gtest/gtest.h>

#include "Components/MPM/Contact/Contact.h"
#include "Core/Util/Errors.h"

namespace anode {
namespace {

// Two materials on three nodes: node 0 holds only material 0, node 1 both, node 2 neither.
std::vector<GridFields> twoMaterials() {
  std::vector<GridFields> f(2);
  for (GridFields& g : f) g.resize(3);
  f[0].mass = {2, 1, 0};
  f[1].mass = {0, 3, 0};
  f[0].velocity = {Vec3(1, 0, 0), Vec3(4, 0, 0), Vec3::Zero()};
  f[1].velocity = {Vec3(9, 9, 9), Vec3(0, 8, 0), Vec3::Zero()};
  return f;
}

Contact readContact(const std::string& contact, int materials) {
  auto spec = ProblemSpec::fromText(
      "<Uintah_specification>\n<MPM>" + contact + "</MPM>\n</Uintah_specification>", "contact.ups");
  return Contact::fromInput(spec->root().requireChild("MPM"), materials);
}

TEST(Contact, SingleVelocityGivesTheCentreOfMassVelocityAtSharedNodes) {
  std::vector<GridFields> f = twoMaterials();
  const Contact c =
      readContact("<contact><type>single_velocity</type><materials>[0,1]</materials></contact>", 2);
  c.exchange(f, &GridFields::velocity, {NodeRange{0, 3}});
  // Node 1: (1 (4,0,0) + 3 (0,8,0)) / 4 = (1, 6, 0) for both; momentum 4 (1,6,0) = (4,0,0) +
  // (0,24,0).
  EXPECT_EQ(f[0].velocity[1], Vec3(1, 6, 0));
  EXPECT_EQ(f[1].velocity[1], Vec3(1, 6, 0));
  // Node 0 has only material 0 (its own velocity is the centre of mass); material 1 has no mass
  // there and takes it too, which carries no momentum.
  EXPECT_EQ(f[0].velocity[0], Vec3(1, 0, 0));
  EXPECT_EQ(f[1].velocity[0], Vec3(1, 0, 0));
  EXPECT_EQ(f[0].velocity[2], Vec3::Zero());
  EXPECT_EQ(f[1].velocity[2], Vec3::Zero());
}

TEST(Contact, NullContactChangesNothing) {
  std::vector<GridFields> f = twoMaterials();
  const Contact c = readContact("<contact><type>null</type></contact>", 2);
  c.exchange(f, &GridFields::velocity, {NodeRange{0, 3}});
  EXPECT_EQ(f[0].velocity[1], Vec3(4, 0, 0));
  EXPECT_EQ(f[1].velocity[1], Vec3(0, 8, 0));
  EXPECT_EQ(readContact("", 2).type, Contact::Type::Null);
}

TEST(Contact, ExcludedMaterialKeepsItsVelocity) {
  std::vector<GridFields> f = twoMaterials();
  const Contact c = readContact(
      "<contact><type>single_velocity</type><ExcludeMaterial>1</ExcludeMaterial></contact>", 2);
  c.exchange(f, &GridFields::velocity, {NodeRange{0, 3}});
  EXPECT_EQ(f[1].velocity[1], Vec3(0, 8, 0));
  EXPECT_EQ(f[0].velocity[1], Vec3(4, 0, 0));
}

// With three materials the other two share a velocity only where the excluded one has no mass
// (Uintah's SingleVelContact), not everywhere.
TEST(Contact, ExcludedMaterialStopsSharingWhereItHasMass) {
  std::vector<GridFields> f = twoMaterials();
  f.resize(3);
  f[2].resize(3);
  f[2].mass = {0, 5, 0};
  f[1].mass = {1, 3, 0};  // material 1 now also at node 0
  const Contact c = readContact(
      "<contact><type>single_velocity</type><ExcludeMaterial>2</ExcludeMaterial></contact>", 3);
  c.exchange(f, &GridFields::velocity, {NodeRange{0, 3}});
  // Node 0 (no material 2): (2 (1,0,0) + 1 (9,9,9)) / 3 for materials 0 and 1.
  EXPECT_EQ(f[0].velocity[0], Vec3(11, 9, 9) / 3);
  EXPECT_EQ(f[1].velocity[0], Vec3(11, 9, 9) / 3);
  // Node 1 (material 2 present): nothing shared.
  EXPECT_EQ(f[0].velocity[1], Vec3(4, 0, 0));
  EXPECT_EQ(f[1].velocity[1], Vec3(0, 8, 0));
}

TEST(Contact, ReadingChecksTheMaterials) {
  EXPECT_THROW(
      readContact("<contact><type>single_velocity</type><materials>[0,2]</materials></contact>", 2),
      InputError);
  EXPECT_THROW(readContact("<contact><type>friction</type></contact>", 2), InputError);
  EXPECT_THROW(
      readContact(
          "<contact><type>single_velocity</type><ExcludeMaterial>5</ExcludeMaterial></contact>", 2),
      InputError);
  EXPECT_FALSE(
      readContact("<contact><type>single_velocity</type><OneOrTwoStep>1</OneOrTwoStep></contact>",
                  2)
          .exchangeInterpolated);
}

}  // namespace
}  // namespace anode
